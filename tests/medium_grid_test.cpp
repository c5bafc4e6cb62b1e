// Heterogeneous media (shared/medium_grid.h) against the laws: the density integral a walk over the
// voxels sums equals the integral along the ray, a grid of ones is the homogeneous medium, free
// flights through a grid are unbiased in every channel (their collisions fall where σs·ρ·T says),
// and a furnace filled with a heterogeneous medium that only scatters stays at radiance 1.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "shared/medium.h"
#include "known_answers.h"
#include "media_scenes.h"
#include "test_render.h"

namespace photon {
namespace {

constexpr double kPi = 3.14159265358979323846;

using test::hashedDensityGrid;

// A scene holding one medium with `grid` (its box the grid's), and the bindings to reach it.
struct GridMedium {
    Scene scene;
    Medium md;
    Bindings bindings{};

    GridMedium(const DensityGrid& grid, glm::vec3 absorption, glm::vec3 scattering) {
        md = homogeneousMedium();
        md.absorption = absorption;
        md.scattering = scattering;
        md.grid = scene.addDensityGrid(grid);
        md.resolution = grid.resolution;
        md.lower = grid.lower;
        md.upper = grid.upper;
        bindings.densities = scene.densities.data();
    }

    // ρ at x by looking the voxel up, for the brute-force sums.
    double rho(glm::dvec3 x, const DensityGrid& grid) const {
        glm::dvec3 u = (x - glm::dvec3(grid.lower)) / glm::dvec3(grid.upper - grid.lower) * glm::dvec3(grid.resolution);
        glm::ivec3 c = glm::clamp(glm::ivec3(glm::floor(u)), glm::ivec3(0), glm::ivec3(grid.resolution) - 1);
        return grid.at(c.x, c.y, c.z);
    }
};

// The integral along a ray by the midpoint rule over many small steps.
double bruteIntegral(const GridMedium& gm, const DensityGrid& grid, glm::vec3 o, glm::vec3 d, double t0, double t1) {
    const int steps = 200000;
    double h = (t1 - t0) / steps;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        sum += gm.rho(glm::dvec3(o) + glm::dvec3(d) * (t0 + (i + 0.5) * h), grid);
    }
    return sum * h;
}

glm::vec3 direction(std::uint32_t i) {
    Rng rng = rngCreate(i, 7u, 1u, STREAM_PHOTON);
    float u1 = rngNext(rng);
    float u2 = rngNext(rng);
    return directionAroundAxis(glm::vec3(0.0f, 0.0f, 1.0f), 2.0f * u1, u2);
}

TEST(MediumGrid, WalkSumsTheDensityIntegral) {
    DensityGrid grid = hashedDensityGrid(glm::uvec3(7, 5, 9), glm::vec3(-1.0f, -0.5f, -2.0f), glm::vec3(1.5f, 0.5f, 1.0f));
    GridMedium gm(grid, glm::vec3(0.0f), glm::vec3(1.0f));
    int crossing = 0;
    for (std::uint32_t i = 0; i < 64; ++i) {
        glm::vec3 o(0.1f, 0.05f, -0.3f);
        glm::vec3 d = direction(i);
        vec2 span = mediumSpan(gm.md, o, d, FLOAT_MAX);
        ASSERT_LT(span.x, span.y);
        double walked = densityIntegral(gm.bindings, gm.md, o, d, span.x, span.y);
        double brute = bruteIntegral(gm, grid, o, d, span.x, span.y);
        EXPECT_NEAR(walked, brute, 2e-3 * std::max(1.0, brute)) << i;
        // From outside: the span starts at the box's face.
        glm::vec3 far = o - 5.0f * d;
        vec2 outside = mediumSpan(gm.md, far, d, FLOAT_MAX);
        double chord = bruteIntegral(gm, grid, far, d, outside.x, outside.y);
        EXPECT_NEAR(densityIntegral(gm.bindings, gm.md, far, d, outside.x, outside.y), chord, 2e-3 * std::max(1.0, chord));
        // Part of the way, and backwards.
        float mid = 0.5f * (span.x + span.y);
        double part = densityIntegral(gm.bindings, gm.md, o, d, span.x, mid);
        EXPECT_NEAR(part, bruteIntegral(gm, grid, o, d, span.x, mid), 2e-3 * std::max(1.0, part)) << i;
        EXPECT_EQ(densityIntegral(gm.bindings, gm.md, o, d, mid, span.x), -float(part));
        crossing += walked > 0.0 ? 1 : 0;
    }
    EXPECT_EQ(crossing, 64);
}

// A target integral is reached where the walk says, and never past the span.
TEST(MediumGrid, WalkStopsWhereTheIntegralIsReached) {
    DensityGrid grid = hashedDensityGrid(glm::uvec3(6, 6, 6), glm::vec3(0.0f), glm::vec3(3.0f));
    GridMedium gm(grid, glm::vec3(0.0f), glm::vec3(1.0f));
    for (std::uint32_t i = 0; i < 64; ++i) {
        glm::vec3 o(1.5f, 1.4f, 1.6f);
        glm::vec3 d = direction(i);
        vec2 span = mediumSpan(gm.md, o, d, FLOAT_MAX);
        float total = densityIntegral(gm.bindings, gm.md, o, d, span.x, span.y);
        for (float share : {0.1f, 0.5f, 0.9f}) {
            DensityWalk w = walkDensity(gm.bindings, gm.md, o, d, span.x, span.y, share * total);
            ASSERT_TRUE(w.reached);
            EXPECT_GE(w.t, span.x);
            EXPECT_LE(w.t, span.y);
            EXPECT_NEAR(densityIntegral(gm.bindings, gm.md, o, d, span.x, w.t), share * total, 1e-4f * std::max(1.0f, total));
        }
        EXPECT_FALSE(walkDensity(gm.bindings, gm.md, o, d, span.x, span.y, 1.001f * total + 1e-3f).reached);
    }
}

// Density 1 everywhere is the homogeneous medium: the same transmittance, the same flights.
TEST(MediumGrid, GridOfOnesIsHomogeneous) {
    DensityGrid grid;
    grid.resolution = glm::uvec3(4, 3, 5);
    grid.lower = glm::vec3(-2.0f);
    grid.upper = glm::vec3(2.0f);
    grid.density.assign(60, 1.0f);
    GridMedium gm(grid, glm::vec3(0.2f, 0.1f, 0.0f), glm::vec3(0.5f, 0.8f, 1.1f));
    Medium plain = gm.md;
    plain.grid = NONE;
    for (std::uint32_t i = 0; i < 2000; ++i) {
        glm::vec3 o(0.3f, -0.2f, 0.1f);
        glm::vec3 d = direction(i);
        vec2 span = mediumSpan(gm.md, o, d, FLOAT_MAX);
        EXPECT_NEAR(densityIntegral(gm.bindings, gm.md, o, d, span.x, span.y), span.y - span.x, 2e-6f);
        Rng a = rngCreate(i, 0u, 5u, STREAM_PHOTON);
        Rng b = a;
        FreeFlight fg = sampleFreeFlight(gm.bindings, gm.md, o, d, span.x, span.y, a);
        FreeFlight fh = sampleFreeFlight(gm.bindings, plain, o, d, span.x, span.y, b);
        ASSERT_EQ(fg.scatters, fh.scatters) << i;
        EXPECT_NEAR(fg.t, fh.t, 4e-6f) << i;
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(fg.weight[c], fh.weight[c], 4e-6f * std::max(1.0f, fh.weight[c])) << i;
        }
    }
}

// Along one ray through a chromatic heterogeneous medium, flights that pass average to
// T = e^(−σt D), and the collisions' weights in each eighth of the span to ∫ σs ρ T dt there.
TEST(MediumGrid, FreeFlightIsUnbiasedInEveryChannel) {
    DensityGrid grid = hashedDensityGrid(glm::uvec3(8, 8, 8), glm::vec3(0.0f), glm::vec3(2.0f));
    GridMedium gm(grid, glm::vec3(0.1f, 0.4f, 0.0f), glm::vec3(0.6f, 0.2f, 0.9f));
    const glm::vec3 o(0.05f, 0.3f, 0.2f);
    const glm::vec3 d = glm::normalize(glm::vec3(1.0f, 0.7f, 0.5f));
    vec2 span = mediumSpan(gm.md, o, d, FLOAT_MAX);
    const int bins = 8;
    const double width = (span.y - span.x) / bins;
    // The expected values by the midpoint rule in double.
    const int steps = 400000;
    double h = (span.y - span.x) / steps;
    std::vector<glm::dvec3> expected(bins, glm::dvec3(0.0));
    double depth = 0.0;
    for (int i = 0; i < steps; ++i) {
        double t = span.x + (i + 0.5) * h;
        double rho = gm.rho(glm::dvec3(o) + glm::dvec3(d) * t, grid);
        double inner = depth + 0.5 * rho * h;  // D at the step's middle
        glm::dvec3 sigmaT = glm::dvec3(gm.md.absorption + gm.md.scattering);
        glm::dvec3 transmittance = glm::exp(-sigmaT * inner);
        expected[std::min(bins - 1, int((t - span.x) / width))] += glm::dvec3(gm.md.scattering) * rho * transmittance * h;
        depth += rho * h;
    }
    glm::dvec3 passes = glm::exp(-glm::dvec3(gm.md.absorption + gm.md.scattering) * depth);
    const std::uint32_t n = 400000;
    std::vector<glm::dvec3> collided(bins, glm::dvec3(0.0));
    glm::dvec3 passed(0.0);
    for (std::uint32_t i = 0; i < n; ++i) {
        Rng rng = rngCreate(i, 0u, 9u, STREAM_PHOTON);
        FreeFlight f = sampleFreeFlight(gm.bindings, gm.md, o, d, span.x, span.y, rng);
        if (f.scatters) {
            ASSERT_TRUE(f.t >= span.x && f.t <= span.y);
            collided[std::min(bins - 1, int((f.t - span.x) / width))] += glm::dvec3(f.weight);
        } else {
            passed += glm::dvec3(f.weight);
        }
    }
    for (int c = 0; c < 3; ++c) {
        std::printf("channel %d: passed %.4f (T %.4f)\n", c, passed[c] / n, passes[c]);
        EXPECT_NEAR(passed[c] / n / passes[c], 1.0, 0.01) << c;
        for (int b = 0; b < bins; ++b) {
            if (expected[b][c] < 0.01) {
                EXPECT_LT(collided[b][c] / n, 0.01) << c << " " << b;
                continue;
            }
            EXPECT_NEAR(collided[b][c] / n / expected[b][c], 1.0, 0.03) << "channel " << c << ", eighth " << b;
        }
    }
}

// The furnace of media_test.cpp with a heterogeneous medium of albedo 1: whatever the density,
// the radiance is 1 everywhere.
TEST(MediumGrid, FurnaceFilledWithHeterogeneousMediumStaysOne) {
    Scene scene;
    DensityGrid grid = hashedDensityGrid(glm::uvec3(6, 6, 6), glm::vec3(-1.0f), glm::vec3(1.0f));
    Medium md = homogeneousMedium();
    md.scattering = glm::vec3(1.5f);
    md.g = 0.4f;
    md.grid = scene.addDensityGrid(grid);
    md.resolution = grid.resolution;
    md.lower = grid.lower;
    md.upper = grid.upper;
    scene.fillWithMedium(scene.addMedium(md));
    const float power = float(kPi) * 4.0f;  // radiance 1 from a 2 × 2 face
    const glm::vec3 x(2.0f, 0.0f, 0.0f), y(0.0f, 2.0f, 0.0f), z(0.0f, 0.0f, 2.0f);
    const glm::vec3 lo(-1.0f), hi(1.0f);
    scene.addQuadLight(lo, x, y, glm::vec3(power));
    scene.addQuadLight(hi, -y, -x, glm::vec3(power));
    scene.addQuadLight(lo, y, z, glm::vec3(power));
    scene.addQuadLight(hi, -z, -y, glm::vec3(power));
    scene.addQuadLight(lo, z, x, glm::vec3(power));
    scene.addQuadLight(hi, -x, -z, glm::vec3(power));
    scene.camera.position = glm::vec3(0.0f, 0.0f, 0.0f);
    scene.camera.lookAt = glm::vec3(0.1f, 0.05f, -1.0f);
    scene.camera.fovY = 90.0f;
    scene.finalize();
    RenderSettings settings = test::sizedSettings({}, 24, 24, 300000);
    settings.maxPhotonDepth = 64;
    settings.deterministic = true;
    settings.volumeRadius = 0.03f;
    // The beam's blur across the voxels' faces is a bias that shrinks with the radius: the mean is
    // 1.025 after 4 frames, 1.013 after 16, 0.999 after 48.
    Image image = test::renderOnCpu(scene, settings, 48);
    double mean = test::meanRed(image);
    std::printf("furnace in a heterogeneous medium: mean radiance %.4f\n", mean);
    EXPECT_NEAR(mean, 1.0, 0.01);
}

}  // namespace
}  // namespace photon
