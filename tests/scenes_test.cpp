// Every shipped scene renders on the CPU reference without NaN or Inf, and is not black. (The GPU
// backends' tests render them too and compare with the CPU.)
#include <gtest/gtest.h>

#include <filesystem>

#include "apps/backends.h"
#include "core/loaders/scene_loader.h"
#include "test_render.h"
#include "test_util.h"

namespace photon {
namespace {

TEST(ShippedScenes, RenderFiniteAndLit) {
    int scenes = 0;
    for (const auto& entry : std::filesystem::directory_iterator(test::scenesDir())) {
        if (entry.path().extension() != ".json") {
            continue;
        }
        SCOPED_TRACE(entry.path().string());
        Scene scene = loadSceneFile(entry.path().string());
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

}  // namespace
}  // namespace photon
