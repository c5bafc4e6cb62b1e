// The scene format's media (docs/scenes.md#media): coefficients, the boxes media fill, density
// grids from OpenVDB files, and one line for each mistake.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/loaders/scene_loader.h"
#include "core/system/error.h"
#include "core/system/numbers.h"
#include "test_util.h"

namespace photon {
namespace {

// A small scene with the given "media" and top-level "medium" (none if empty), read as if it lay
// in the scenes folder (so that "smoke.vdb" is found).
std::string sceneText(const std::string& media, const std::string& medium) {
    return R"({"camera": {"position": [0, 1, 4], "look_at": [0, 1, 0]},
               "materials": {"white": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]}},
               "objects": [{"type": "quad", "corner": [-1, 0, -1], "edge_u": [0, 0, 2], "edge_v": [2, 0, 0], "material": "white"}],
               "lights": [{"type": "point", "position": [0, 1.5, 0], "power": 10}],
               "media": )" + media + (medium.empty() ? "" : R"(, "medium": )" + medium) + "}";
}

Scene load(const std::string& media, const std::string& medium) {
    return loadSceneJson(sceneText(media, medium), "x.json", test::scenesDir() + "/");
}

std::string errorOf(const std::string& media, const std::string& medium) {
    try {
        load(media, medium);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(loaded)";
}

TEST(SceneMedia, DensityAndAlbedoGiveTheCoefficients) {
    Scene s = load(R"({"milk": {"density": [2, 4, 8], "albedo": [0.5, 0.75, 1], "g": 0.4}})", R"("milk")");
    ASSERT_EQ(s.media.size(), 1u);
    const Medium& md = s.media[s.medium];
    EXPECT_EQ(md.scattering, glm::vec3(1.0f, 3.0f, 8.0f));
    EXPECT_EQ(md.absorption, glm::vec3(1.0f, 1.0f, 0.0f));
    EXPECT_EQ(md.g, 0.4f);
    EXPECT_EQ(md.grid, NONE);
    // Without a box, the scene's bounds (with a margin).
    EXPECT_LE(md.lower.x, s.boundsMin.x);
    EXPECT_GE(md.upper.x, s.boundsMax.x);
}

// The range's ends are accepted as written: 0.99 as a float lies above 0.99 and was refused as
// "must be in [-0.99, 0.99] (got 0.99)" (issue 57).
TEST(SceneMedia, TheEndsOfARangeAreAccepted) {
    for (double g : {0.99, -0.99}) {
        Scene s = load(R"({"fog": {"scattering": 0.2, "g": )" + formatNumber(g) + "}}", R"("fog")");
        EXPECT_LE(std::abs(s.media[s.medium].g), 0.99f);
        EXPECT_NEAR(s.media[s.medium].g, g, 1e-6);
    }
    EXPECT_NE(errorOf(R"({"fog": {"scattering": 0.2, "g": 0.995}})", "").find("must be in [-0.99, 0.99] (got 0.995)"),
              std::string::npos);
}

TEST(SceneMedia, MediumFillsTheBoxGiven) {
    Scene s = load(R"({"fog": {"scattering": 0.2}})", R"({"name": "fog", "min": [-3, 0, -3], "max": [3, 2, 3]})");
    EXPECT_EQ(s.media[s.medium].lower, glm::vec3(-3.0f, 0.0f, -3.0f));
    EXPECT_EQ(s.media[s.medium].upper, glm::vec3(3.0f, 2.0f, 3.0f));
    // The box holds light the camera sees: the scene's bounds take it in.
    EXPECT_EQ(s.boundsMin.x, -3.0f);
}

TEST(SceneMedia, MistakesAreNamed) {
    EXPECT_NE(errorOf(R"({"fog": {"scattering": 0.2}})", R"("smog")").find("unknown medium 'smog' (the scene's \"media\" name fog)"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"fog": {"scattering": 0.2, "density": 1}})", "").find("not both"), std::string::npos);
    EXPECT_NE(errorOf(R"({"fog": {"scattering": -1}})", "").find("/media/fog/scattering"), std::string::npos);
    EXPECT_NE(errorOf(R"({"fog": {"scattering": 0.2, "g": 1}})", "").find("/media/fog/g"), std::string::npos);
    EXPECT_NE(errorOf(R"({"fog": {"scattering": 0.2}})", R"({"name": "fog", "min": [0, 0, 0], "max": [1, 0, 1]})")
                  .find("must exceed min"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"fog": {"scattering": 0.2, "grid": {"file": "no-such.vdb"}}})", "").find("no-such.vdb"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"fog": {"scattering": 0.2, "grid": {"file": "smoke.vdb", "resolution": 0}}})", "")
                  .find("/media/fog/grid/resolution"),
              std::string::npos);
}

#ifdef PHOTON_TESTS_READ_OPENVDB
// smoke.json's grid: the box of the file's active voxels (of its 64 × 128 × 64), placed in the box
// the scene gives.
TEST(SceneMedia, GridFromAnOpenVdbFile) {
    Scene s = loadSceneFile(test::scenesDir() + "/smoke.json");
    const Medium& md = s.media[s.medium];
    ASSERT_NE(md.grid, NONE);
    EXPECT_EQ(md.resolution, glm::uvec3(49, 121, 50));
    EXPECT_EQ(md.lower, glm::vec3(-0.45f, 0.0f, -0.45f));
    EXPECT_EQ(md.upper, glm::vec3(0.45f, 1.8f, 0.45f));
    EXPECT_EQ(s.densities.size(), 49u * 121u * 50u);
    float most = 0.0f;
    for (float d : s.densities) {
        most = std::max(most, d);
    }
    EXPECT_GT(most, 0.3f);
}

TEST(SceneMedia, GridIsAveragedDownToTheResolutionAsked) {
    Scene s = load(R"({"smoke": {"scattering": 5, "grid": {"file": "smoke.vdb", "resolution": 32}}})", R"("smoke")");
    const Medium& md = s.media[s.medium];
    EXPECT_EQ(md.resolution, glm::uvec3(13, 31, 13));  // blocks of 4³: 49, 121, 50 voxels, rounded up
    // Without min and max, where the file puts it: 121 voxels of 2/128 (and the 3 voxels the last
    // block reaches past them).
    EXPECT_NEAR(md.upper.y - md.lower.y, 124.0f * 2.0f / 128.0f, 1e-4f);
}

TEST(SceneMedia, GridMediumTakesNoBoxOfItsOwn) {
    EXPECT_NE(errorOf(R"({"smoke": {"scattering": 5, "grid": {"file": "smoke.vdb"}}})",
                      R"({"name": "smoke", "min": [0, 0, 0], "max": [1, 1, 1]})")
                  .find("place the grid with its own min and max"),
              std::string::npos);
}
#endif

}  // namespace
}  // namespace photon
