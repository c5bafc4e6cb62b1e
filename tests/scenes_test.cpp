// Every shipped scene renders on the CPU reference without NaN or Inf, and is not black. (The GPU
// backends' tests render them too and compare with the CPU.)
#include <gtest/gtest.h>

#include <filesystem>

#include "core/render/devices.h"
#include "core/loaders/scene_loader.h"
#include "test_render.h"
#include "test_util.h"

namespace photon {
namespace {

TEST(ShippedScenes, RenderFiniteAndLit) {
    int scenes = 0;
    for (const std::string& path : test::shippedScenes({".json"})) {
        SCOPED_TRACE(path);
        Scene scene = loadSceneFile(path);
        for (Estimator e : {Estimator::Radius, Estimator::Knn, Estimator::Cell, Estimator::Progressive}) {
            RenderSettings s = test::sizedSettings(scene.render, 64, 48, 20000);
            s.estimator = e;
            Image image = test::renderOnCpu(scene, s, 2);
            EXPECT_TRUE(allFinite(image)) << toString(e);
            EXPECT_GT(meanLuminance(image), 0.0) << toString(e);
        }
        scenes += 1;
    }
    EXPECT_GE(scenes, 5);
}

// A surface so far away that points on it overflow the float range, seen through a mirror: rays
// that reach it leave the scene instead of bringing an infinite point back (the render fuzzer's
// find: a spot light's direction from such a point was NaN).
TEST(ShippedScenes, SurfacesBeyondTheFloatRangeAreOutOfReach) {
    const std::string text = R"({"camera": {"position": [-0.54, -0.015, 2.8], "look_at": [0.215, -0.234, -0.788], "fov": 12.2},
        "materials": {"mirror": {"type": "mirror"}, "wall": {"type": "reflective", "albedo": [0.4, 0.2, 0.1], "reflectance": [0.5, 0.5, 0.5]}},
        "objects": [{"type": "plane", "point": [-1.31, 1e38, -3.21], "normal": [-0.871, 0.926, 2.372], "material": "mirror"},
                    {"type": "plane", "point": [1e-45, -1.93, -2.89], "normal": [-0.097, 1.199, 3.829], "material": "wall"}],
        "lights": [{"type": "spot", "position": [-3.47, 3.54, -3.11], "direction": [1.189, -2.433, -0.225], "angle": 43.9, "power": 1.2}]})";
    Scene scene = loadSceneJson(text, "far-mirror.json");
    RenderSettings s = test::sizedSettings(scene.render, 12, 10, 1500);
    Image image = test::renderOnCpu(scene, s, 2);
    EXPECT_TRUE(allFinite(image));
}

}  // namespace
}  // namespace photon
