// The procedural smoke plume (tools/smoke_field.h): densities in [0, 1] that vanish at the box's
// faces, the same for the same seed, and shaped like smoke: a thin stem that widens as it rises,
// with holes torn in it.
#include "tools/smoke_field.h"

#include <gtest/gtest.h>

#include <cmath>

namespace photon {
namespace {

TEST(SmokeField, ValueNoiseIsSmoothAndInRange) {
    for (int i = 0; i < 2000; ++i) {
        glm::vec3 p(0.37f * float(i), -0.11f * float(i % 97), 0.05f * float(i % 31) - 3.0f);
        float n = tools::valueNoise(p, 9);
        ASSERT_GE(n, 0.0f);
        ASSERT_LE(n, 1.0f);
        EXPECT_NEAR(tools::valueNoise(p + glm::vec3(1e-3f, 0.0f, 0.0f), 9), n, 0.01f);  // continuous, across lattice planes too
        float f = tools::fractalNoise(p, 9, 5);
        ASSERT_GE(f, -1.0f);
        ASSERT_LE(f, 1.0f);
    }
    EXPECT_EQ(tools::valueNoise(glm::vec3(0.5f, 1.5f, 2.5f), 3), tools::valueNoise(glm::vec3(0.5f, 1.5f, 2.5f), 3));
    EXPECT_NE(tools::valueNoise(glm::vec3(0.5f, 1.5f, 2.5f), 3), tools::valueNoise(glm::vec3(0.5f, 1.5f, 2.5f), 4));
}

TEST(SmokeField, PlumeLooksLikeSmoke) {
    const glm::uvec3 n(64, 128, 64);
    DensityGrid plume = tools::makeSmokePlume(n, 2);
    ASSERT_EQ(plume.resolution, n);
    ASSERT_EQ(plume.density.size(), std::size_t(n.x) * n.y * n.z);
    EXPECT_EQ(plume.lower, glm::vec3(-0.5f, 0.0f, -0.5f));
    EXPECT_EQ(plume.upper, glm::vec3(0.5f, 2.0f, 0.5f));
    float largest = 0.0f;
    for (std::uint32_t z = 0; z < n.z; ++z) {
        for (std::uint32_t y = 0; y < n.y; ++y) {
            for (std::uint32_t x = 0; x < n.x; ++x) {
                float d = plume.at(x, y, z);
                ASSERT_TRUE(d >= 0.0f && d <= 1.0f) << d;
                largest = std::max(largest, d);
                // Nothing is cut off: the two outer layers of voxels hold no smoke.
                if (x < 2 || y < 2 || z < 2 || x >= n.x - 2 || y >= n.y - 2 || z >= n.z - 2) {
                    ASSERT_EQ(d, 0.0f) << x << ", " << y << ", " << z;
                }
            }
        }
    }
    EXPECT_GT(largest, 0.7f);

    // The area of a horizontal slice holding smoke (> 0.01), and the holes inside its bounding
    // square: low down a thin solid stem, high up a wide torn cloud.
    auto slice = [&](std::uint32_t y, std::uint32_t& holes) {
        std::uint32_t smoke = 0;
        glm::uvec2 first(n.x), last(0u);
        for (std::uint32_t z = 0; z < n.z; ++z) {
            for (std::uint32_t x = 0; x < n.x; ++x) {
                if (plume.at(x, y, z) > 0.01f) {
                    ++smoke;
                    first = glm::min(first, glm::uvec2(x, z));
                    last = glm::max(last, glm::uvec2(x, z));
                }
            }
        }
        holes = smoke == 0 ? 0 : (last.x - first.x + 1) * (last.y - first.y + 1) - smoke;
        return smoke;
    };
    std::uint32_t lowHoles = 0;
    std::uint32_t highHoles = 0;
    std::uint32_t low = slice(n.y / 10, lowHoles);       // y = 0.2
    std::uint32_t high = slice(n.y * 7 / 10, highHoles);  // y = 1.4
    EXPECT_GT(low, 0u);
    EXPECT_GT(high, 4 * low);
    EXPECT_GT(highHoles, high / 4);

    // A seed is a plume: the same one again, another one different.
    EXPECT_EQ(tools::makeSmokePlume(glm::uvec3(8, 16, 8), 7).density, tools::makeSmokePlume(glm::uvec3(8, 16, 8), 7).density);
    EXPECT_NE(tools::makeSmokePlume(glm::uvec3(8, 16, 8), 7).density, tools::makeSmokePlume(glm::uvec3(8, 16, 8), 8).density);
}

}  // namespace
}  // namespace photon
