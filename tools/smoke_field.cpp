#include "tools/smoke_field.h"

#include <cmath>

namespace photon::tools {
namespace {

// Chris Wellons' "lowbias32" integer hash: every input bit flips about half the output bits.
std::uint32_t mix(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// The value at lattice point (x, y, z), in [0, 1).
float latticeValue(std::int32_t x, std::int32_t y, std::int32_t z, std::uint32_t seed) {
    std::uint32_t h = mix(seed ^ 0x9e3779b9u);
    h = mix(h ^ std::uint32_t(x));
    h = mix(h ^ std::uint32_t(y));
    h = mix(h ^ std::uint32_t(z));
    return float(h >> 8) * (1.0f / 16777216.0f);
}

// Perlin's quintic fade 6t⁵ − 15t⁴ + 10t³: its first and second derivatives vanish at 0 and 1,
// so the noise has no creases along the lattice planes.
float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

float smoothstep(float edge0, float edge1, float x) {
    float t = glm::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// Offsets that make one seed's three noise fields (the warp's x, y, z) independent.
constexpr glm::vec3 kWarpOffset[3] = {{17.3f, 5.1f, -9.7f}, {-31.9f, 12.4f, 3.3f}, {7.7f, -23.5f, 41.2f}};

}  // namespace

float valueNoise(glm::vec3 p, std::uint32_t seed) {
    glm::vec3 cell = glm::floor(p);
    glm::vec3 t = p - cell;
    auto x = std::int32_t(cell.x);
    auto y = std::int32_t(cell.y);
    auto z = std::int32_t(cell.z);
    float u = fade(t.x);
    float v = fade(t.y);
    float w = fade(t.z);
    auto lerp = [](float a, float b, float s) { return a + (b - a) * s; };
    float x00 = lerp(latticeValue(x, y, z, seed), latticeValue(x + 1, y, z, seed), u);
    float x10 = lerp(latticeValue(x, y + 1, z, seed), latticeValue(x + 1, y + 1, z, seed), u);
    float x01 = lerp(latticeValue(x, y, z + 1, seed), latticeValue(x + 1, y, z + 1, seed), u);
    float x11 = lerp(latticeValue(x, y + 1, z + 1, seed), latticeValue(x + 1, y + 1, z + 1, seed), u);
    return lerp(lerp(x00, x10, v), lerp(x01, x11, v), w);
}

float fractalNoise(glm::vec3 p, std::uint32_t seed, int octaves) {
    float sum = 0.0f;
    float amplitude = 1.0f;
    float total = 0.0f;
    for (int octave = 0; octave < octaves; ++octave) {
        sum += amplitude * (2.0f * valueNoise(p, seed + std::uint32_t(octave) * 0x632be5abu) - 1.0f);
        total += amplitude;
        amplitude *= 0.5f;
        p *= 2.0f;
    }
    return sum / total;
}

// The plume, height h = y / 2 from 0 to 1:
// - a column about the y axis of radius R(h) = 0.05 + 0.25 h, whose density falls off from its
//   axis as a Gaussian and thins as (R(0) / R(h))^1.5 as it spreads (the smoke it carries shared
//   by a wider cross-section, a little lost on the way);
// - twisted about the axis by an angle growing with height, and its points displaced (domain
//   warping, Quilez) by three fractal noise fields of growing amplitude: the column sways, curls
//   and breaks into eddies higher up;
// - torn into wisps and holes by a finer fractal noise through a smoothstep threshold;
// - faded in over the source (0.04 < y < 0.12), out at the top, and to 0 within 0.04 of the sides
//   and the top: the box holds all of it.
float smokeDensity(glm::vec3 p, std::uint32_t seed) {
    float h = glm::clamp(p.y / (kSmokeUpper.y - kSmokeLower.y), 0.0f, 1.0f);
    // The axis drifts sideways as the column rises (slow noise in y alone).
    float drift = 0.5f * std::pow(h, 1.5f);
    glm::vec3 q = p - drift * glm::vec3(fractalNoise(glm::vec3(0.0f, 0.8f * p.y, 0.0f) + kWarpOffset[0], seed + 7u, 2), 0.0f,
                                        fractalNoise(glm::vec3(0.0f, 0.8f * p.y, 0.0f) + kWarpOffset[1], seed + 8u, 2));
    float twist = 3.0f * h;
    q = glm::vec3(std::cos(twist) * q.x - std::sin(twist) * q.z, q.y, std::sin(twist) * q.x + std::cos(twist) * q.z);
    float sway = 0.02f + 0.2f * h;
    glm::vec3 warp;
    for (int k = 0; k < 3; ++k) {
        warp[k] = fractalNoise(p * 2.0f + kWarpOffset[k], seed + std::uint32_t(k) + 1u, 3);
    }
    q += sway * glm::vec3(warp.x, 0.5f * warp.y, warp.z);

    // Billows: the column's edge pushed in and out by mid-frequency noise, then a soft edge.
    float radius = 0.03f + 0.25f * h;
    float billow = fractalNoise(q * 4.0f + glm::vec3(3.1f, -2.0f * p.y, 1.3f), seed + 4u, 3);
    float r = std::sqrt(q.x * q.x + q.z * q.z) / radius + 0.9f * billow * glm::min(1.0f, 4.0f * h);
    float column = smoothstep(1.3f, 0.2f, r) * (1.0f - 0.6f * h);

    // Wisps and holes: finer noise through a threshold that rises with height, none at the source.
    float detail = fractalNoise(q * glm::vec3(7.0f, 4.0f, 7.0f) + glm::vec3(0.0f, -1.7f, 0.0f), seed, 4);
    float wisps = glm::mix(1.0f, smoothstep(0.3f * h - 0.25f, 0.3f * h + 0.05f, detail), smoothstep(0.05f, 0.3f, h));

    float fade = smoothstep(0.04f, 0.12f, p.y) * (1.0f - smoothstep(1.7f, 1.94f, p.y));
    float sides = smoothstep(0.46f, 0.38f, std::abs(p.x)) * smoothstep(0.46f, 0.38f, std::abs(p.z));
    return glm::clamp(column * wisps * fade * sides, 0.0f, 1.0f);
}

DensityGrid makeSmokePlume(glm::uvec3 resolution, std::uint32_t seed) {
    DensityGrid grid;
    grid.resolution = resolution;
    grid.lower = kSmokeLower;
    grid.upper = kSmokeUpper;
    grid.density.resize(std::size_t(resolution.x) * resolution.y * resolution.z);
    glm::vec3 voxel = (kSmokeUpper - kSmokeLower) / glm::vec3(resolution);
    std::size_t i = 0;
    for (std::uint32_t z = 0; z < resolution.z; ++z) {
        for (std::uint32_t y = 0; y < resolution.y; ++y) {
            for (std::uint32_t x = 0; x < resolution.x; ++x) {
                glm::vec3 centre = kSmokeLower + (glm::vec3(x, y, z) + 0.5f) * voxel;
                grid.density[i++] = smokeDensity(centre, seed);
            }
        }
    }
    return grid;
}

}  // namespace photon::tools
