// The environment light (LIGHT_ENVIRONMENT): radiance arriving from every direction that leaves
// the scene, uniform or read from an equirectangular (latitude-longitude) map, and its importance
// sampling by a 2D piecewise-constant distribution over the map (pbrt-v4's PiecewiseConstant2D;
// for a latitude-longitude map each texel weighted by luminance × sin θ, as Mitsuba 3 and LuxCore
// do), for shadow rays and for photons.
//
// Conventions (docs/scenes.md): +Y is up. A map's row 0 is the zenith and its last row the nadir,
// v = θ/π with θ measured from +Y. The image's centre column (u = 0.5) lies along −Z, where a
// default camera looks, and u grows towards +X, so that the panorama seen from inside is not
// mirrored:   d(u, v) = (sin θ sin φ, cos θ, −sin θ cos φ),  φ = 2π(u − 0.5),  θ = πv.
// A rotation R turns the map in the world: a world direction d looks up the map at Rᵀd.
//
// Buffers: environmentTexels holds the map's texels row by row in Radiance's shared-exponent RGBE
// (8-bit mantissas, one 8-bit exponent: the range of float at 4 bytes a texel); environmentCdf the
// distribution, normalised: the marginal cdf over rows (height + 1 entries, 0 … 1), then each
// row's conditional cdf over its columns (width + 1 entries each). The density of a sample is the
// product of the two cdf steps it fell in, exactly the probability the search below gives it.
#ifndef PHOTON_SHARED_ENVIRONMENT_H
#define PHOTON_SHARED_ENVIRONMENT_H

#include "bindings.h"
#include "light_types.h"
#include "sampling.h"

PH_NAMESPACE_BEGIN

PH_CONST float TWO_PI_SQUARED = 19.7392088021787172f;  // 2π²: dω = 2π² sin θ du dv

// Radiance's RGBE texel (r | g << 8 | b << 16 | e << 24): (m + 0.5) · 2^(e − 136), e = 0 is black.
// The power of two is built from its bits, so every backend decodes the same value.
PH_FN vec3 decodeRgbe(uint texel) {
    uint e = texel >> 24u;
    if (e <= 1u) {
        return vec3(0.0f);  // (e = 1 would be 2^-135 and below: nothing a renderer sees)
    }
    float scale = uintBitsToFloat((e - 1u) << 23u) * (1.0f / 256.0f);  // 2^(e − 128) / 256
    return vec3(float(texel & 255u) + 0.5f, float((texel >> 8u) & 255u) + 0.5f, float((texel >> 16u) & 255u) + 0.5f) *
           scale;
}

// The map direction of map coordinates (u, v) ∈ [0, 1]²; polynomial sines (math.h), since photon
// directions come from here.
PH_FN vec3 equirectDirection(float u, float v) {
    float sinPhi;
    float cosPhi;
    sinCos2Pi(u - 0.5f, sinPhi, cosPhi);
    float sinTheta;
    float cosTheta;
    sinCos2Pi(0.5f * v, sinTheta, cosTheta);
    sinTheta = max(sinTheta, 0.0f);
    return vec3(sinTheta * sinPhi, cosTheta, -sinTheta * cosPhi);
}

// The map coordinates of a unit map direction (polynomial arctangents, math.h: the texel a
// direction looks up is the same on every backend).
PH_FN vec2 equirectCoordinates(vec3 d) {
    float u = 0.5f + atan2Poly(d.x, -d.z) * INV_TWO_PI;
    float sinTheta = sqrt(max(0.0f, d.x * d.x + d.z * d.z));
    float v = clamp(atan2Poly(sinTheta, d.y) * INV_PI, 0.0f, 1.0f);
    return vec2(u - floor(u), v);
}

PH_FN vec3 environmentToMap(PH_IN(Light) light, vec3 world) {
    return vec3(dot(world, environmentMapX(light)), dot(world, environmentMapY(light)),
                dot(world, environmentMapZ(light)));
}

PH_FN vec3 environmentToWorld(PH_IN(Light) light, vec3 d) {
    return environmentMapX(light) * d.x + environmentMapY(light) * d.y + environmentMapZ(light) * d.z;
}

PH_FN uvec2 environmentTexel(PH_IN(Light) light, vec2 uv) {
    uint w = environmentWidth(light);
    uint h = environmentHeight(light);
    return uvec2(min(uint(uv.x * float(w)), w - 1u), min(uint(uv.y * float(h)), h - 1u));
}

// Radiance [W·sr⁻¹·m⁻²] arriving from the unit world direction `toward` (pointing away from the
// scene): the texel it falls in (nearest, so that radiance and sampling density share their
// support), scaled.
PH_FN vec3 environmentRadiance(BUF_PARAM PH_IN(Light) light, vec3 toward) {
    if (environmentHeight(light) == 0u) {
        return environmentScale(light);
    }
    uvec2 t = environmentTexel(light, equirectCoordinates(environmentToMap(light, toward)));
    return decodeRgbe(BUF(environmentTexels)[t.y * environmentWidth(light) + t.x]) * environmentScale(light);
}

// The bin i of cdf[first .. first + count] (cdf[first] = 0, cdf[first + count] = 1) that u ∈ [0, 1)
// falls in: the last with cdf[first + i] ≤ u, which is never a bin of zero width.
PH_FN uint searchEnvironmentCdf(BUF_PARAM uint first, uint count, float u) {
    uint lo = 0u;
    uint hi = count - 1u;
    while (lo < hi) {
        uint mid = (lo + hi + 1u) / 2u;
        if (BUF(environmentCdf)[first + mid] <= u) {
            lo = mid;
        } else {
            hi = mid - 1u;
        }
    }
    return lo;
}

PH_FN uint environmentRowCdf(PH_IN(Light) light, uint row) {
    return environmentHeight(light) + 1u + row * (environmentWidth(light) + 1u);
}

// The density in (u, v) of the map's texel t: the probabilities of its row and of its column in
// that row, times the texel count.
PH_FN float environmentTexelDensity(BUF_PARAM PH_IN(Light) light, uvec2 t) {
    uint w = environmentWidth(light);
    uint h = environmentHeight(light);
    uint row = environmentRowCdf(light, t.y);
    float pRow = BUF(environmentCdf)[t.y + 1u] - BUF(environmentCdf)[t.y];
    float pColumn = BUF(environmentCdf)[row + t.x + 1u] - BUF(environmentCdf)[row + t.x];
    PH_PRECISE float density = pRow * pColumn * float(w * h);
    return density;
}

// A direction towards the environment (unit, world space) drawn in proportion to its luminance,
// with its density per solid angle (pdf, 0 where none is drawn) and the radiance from there.
PH_FN vec3 sampleEnvironment(BUF_PARAM PH_IN(Light) light, float u1, float u2, PH_OUT(vec3) toward, PH_OUT(float) pdf) {
    uint w = environmentWidth(light);
    uint h = environmentHeight(light);
    if (h == 0u) {
        toward = sampleUniformSphere(u1, u2);
        pdf = INV_FOUR_PI;
        return environmentScale(light);
    }
    uint y = searchEnvironmentCdf(BUF_ARG 0u, h, u2);
    float r0 = BUF(environmentCdf)[y];
    float r1 = BUF(environmentCdf)[y + 1u];
    uint row = environmentRowCdf(light, y);
    uint x = searchEnvironmentCdf(BUF_ARG row, w, u1);
    float c0 = BUF(environmentCdf)[row + x];
    float c1 = BUF(environmentCdf)[row + x + 1u];
    // Where u1 and u2 fall within their bins, mapped linearly onto the texel.
    float v = (float(y) + clamp((u2 - r0) / (r1 - r0), 0.0f, 1.0f)) / float(h);
    float u = (float(x) + clamp((u1 - c0) / (c1 - c0), 0.0f, 1.0f)) / float(w);
    vec3 d = equirectDirection(u, v);
    toward = environmentToWorld(light, d);
    float sinTheta = sqrt(max(0.0f, 1.0f - d.y * d.y));
    // dω = 2π² sin θ du dv. (precise: Mesa would fold and reorder the constant factors, and the
    // photons' power would differ from the CPU's in the last bit.)
    PH_PRECISE float density = (r1 - r0) * (c1 - c0) * float(w * h);
    PH_PRECISE float jacobian = TWO_PI_SQUARED * sinTheta;
    pdf = sinTheta > 0.0f ? density / jacobian : 0.0f;
    return decodeRgbe(BUF(environmentTexels)[y * w + x]) * environmentScale(light);
}

// The density per solid angle with which sampleEnvironment draws the unit world direction
// `toward`.
PH_FN float environmentPdf(BUF_PARAM PH_IN(Light) light, vec3 toward) {
    if (environmentHeight(light) == 0u) {
        return INV_FOUR_PI;
    }
    vec3 d = environmentToMap(light, toward);
    float sinTheta = sqrt(max(0.0f, 1.0f - d.y * d.y));
    if (!(sinTheta > 0.0f)) {
        return 0.0f;
    }
    uvec2 t = environmentTexel(light, equirectCoordinates(d));
    PH_PRECISE float jacobian = TWO_PI_SQUARED * sinTheta;
    return environmentTexelDensity(BUF_ARG light, t) / jacobian;
}

PH_NAMESPACE_END

#endif
