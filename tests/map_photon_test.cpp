// The photon maps' 16-byte photon (shared/map_photon.h): what it keeps of a photon's position,
// direction and power, and that its rounding of powers is unbiased.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "shared/map_photon.h"
#include "shared/math.h"

namespace photon {
namespace {

GridParams hashedGrid() {
    GridParams g{};
    g.origin = glm::vec3(1.5f, -2.0f, 3.25f);
    g.cellSize = 0.01f;
    g.kind = GRID_HASHED;
    g.cellCount = 1u << 16;
    return g;
}

Photon photonAt(glm::vec3 position, glm::vec3 incoming, glm::vec3 power, std::uint32_t id) {
    Photon p{};
    p.position = position;
    p.incoming = octEncode(incoming);
    p.power = power;
    p.id = id;
    return p;
}

TEST(MapPhoton, PositionWithinItsRoundingAndWhereTheMapFilesIt) {
    GridParams grid = hashedGrid();
    Rng rng = rngCreate(1u, 0u, 0u, STREAM_PHOTON);
    for (int i = 0; i < 100000; ++i) {
        float scale = std::exp2(rngNext(rng) * 20.0f - 10.0f);  // 1e-3 .. 1e3 from the origin
        glm::vec3 p = grid.origin + scale * (glm::vec3(rngNext(rng), rngNext(rng), rngNext(rng)) - 0.5f);
        Photon decoded = decodeMapPhoton(encodeMapPhoton(photonAt(p, glm::vec3(0, 0, 1), glm::vec3(1.0f), i), grid, 0, 0), grid);
        glm::vec3 kept = mapPosition(p, grid);
        ASSERT_EQ(std::memcmp(&decoded.position, &kept, sizeof kept), 0) << "the count step's position differs";
        for (int a = 0; a < 3; ++a) {
            double offset = std::abs(double(p[a]) - double(grid.origin[a]));
            // 2^-16 of the offset, and the rounding of the subtraction and of adding the origin back.
            double bound = offset * std::exp2(-16.0) + 2.0 * std::abs(double(grid.origin[a])) * std::exp2(-24.0);
            ASSERT_LE(std::abs(double(decoded.position[a]) - double(p[a])), bound) << "axis " << a << " at " << p[a];
        }
    }
}

TEST(MapPhoton, DirectionWithinATenthOfADegree) {
    GridParams grid = hashedGrid();
    Rng rng = rngCreate(2u, 0u, 0u, STREAM_PHOTON);
    double worst = 0.0;
    for (int i = 0; i < 100000; ++i) {
        float z = 2.0f * rngNext(rng) - 1.0f;
        float phi = 6.2831853f * rngNext(rng);
        float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
        glm::vec3 w(s * std::cos(phi), s * std::sin(phi), z);
        Photon decoded = decodeMapPhoton(encodeMapPhoton(photonAt(grid.origin, w, glm::vec3(1.0f), i), grid, 0, 0), grid);
        double c = std::clamp(double(glm::dot(octDecode(decoded.incoming), w)), -1.0, 1.0);
        worst = std::max(worst, std::acos(c) * 180.0 / 3.14159265358979);
    }
    std::printf("worst direction error: %.4f degrees\n", worst);
    EXPECT_LT(worst, 0.1);  // 0.07 measured
}

// The mean of many photons of one power, as the maps keep them, against that power; and each
// photon's largest channel within one step (1/128 of it).
void expectKeptInExpectation(glm::vec3 power) {
    SCOPED_TRACE(testing::Message() << "power " << power.x << " " << power.y << " " << power.z);
    GridParams grid = hashedGrid();
    constexpr int kPhotons = 200000;
    glm::dvec3 sum(0.0);
    glm::dvec3 sumSquares(0.0);
    float largest = std::max(power.x, std::max(power.y, power.z));
    for (int i = 0; i < kPhotons; ++i) {
        glm::vec3 kept = decodeMapPhoton(encodeMapPhoton(photonAt(grid.origin, glm::vec3(0, 0, 1), power, i), grid, 3, 5), grid).power;
        for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(kept[c]));
            ASSERT_LE(std::abs(kept[c] - power[c]), largest / 128.0f) << "channel " << c;
            if (power[c] == 0.0f) {
                ASSERT_EQ(kept[c], 0.0f) << "a channel of zero must stay zero";
            }
        }
        sum += glm::dvec3(kept);
        sumSquares += glm::dvec3(kept) * glm::dvec3(kept);
    }
    for (int c = 0; c < 3; ++c) {
        double mean = sum[c] / kPhotons;
        double sigma = std::sqrt(std::max(0.0, sumSquares[c] / kPhotons - mean * mean) / kPhotons);
        EXPECT_LE(std::abs(mean - double(power[c])), 4.0 * sigma + 1e-6 * double(largest)) << "channel " << c;
    }
}

TEST(MapPhoton, PowerIsKeptInExpectation) {
    expectKeptInExpectation(glm::vec3(1.0f));
    expectKeptInExpectation(glm::vec3(0.8f, 0.05f, 0.3f) * 1.0e-4f);  // a dim channel: 3 of 256 steps
    expectKeptInExpectation(glm::vec3(0.0f, 3.0e-7f, 0.0f));          // dispersed to one wavelength
    expectKeptInExpectation(glm::vec3(0.9995f, 0.4f, 0.002f) * 0.125f);  // a largest mantissa above 255
    expectKeptInExpectation(glm::vec3(2.0e20f, 1.0e19f, 3.0e20f));
    expectKeptInExpectation(glm::vec3(1.0e-30f, 5.0e-31f, 2.0e-32f));
}

TEST(MapPhoton, NoPowerAndUnderflowAreNone) {
    GridParams grid = hashedGrid();
    for (glm::vec3 power : {glm::vec3(0.0f), glm::vec3(1.0e-37f), glm::vec3(-1.0f)}) {
        glm::vec3 kept = decodeMapPhoton(encodeMapPhoton(photonAt(grid.origin, glm::vec3(0, 0, 1), power, 9), grid, 0, 0), grid).power;
        EXPECT_EQ(kept, glm::vec3(0.0f));
    }
}

}  // namespace
}  // namespace photon
