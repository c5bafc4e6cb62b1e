// Several devices render one frame together (core/frame/collective.h): each traces its range of
// the photon paths, the photons meet in the first device's maps, which runs the rest. With
// deterministic maps the image must be one device's, bit for bit, whatever the number of devices,
// the scene (area lights, an environment, caustics), the estimator or a map that overflows.
#include <gtest/gtest.h>

#include <cstring>

#include "core/loaders/scene_loader.h"
#include "core/render/devices.h"
#include "core/render/render_stats.h"
#include "core/system/error.h"
#include "backend_compare.h"
#include "test_util.h"

namespace photon {
namespace {

struct Rendered {
    Image image;
    FrameStats last;
};

Rendered renderOn(const std::string& backends, const Scene& scene, const RenderSettings& settings, int frames) {
    auto renderer = createRenderer(backends);
    EXPECT_EQ(renderer->deviceCount(), std::size_t(std::count(backends.begin(), backends.end(), ',') + 1));
    renderer->setScene(scene);
    renderer->setSettings(settings);
    for (int f = 0; f < frames; ++f) {
        renderer->renderFrame();
    }
    return {renderer->image(), renderer->lastFrameStats()};
}

// Bit for bit; on failure writes both images and their difference to the test output folder.
void expectIdentical(const Image& actual, const Image& expected, const std::string& name) {
    std::size_t differing = test::differingPixels(actual, expected);
    if (differing > 0) {
        test::expectImagesClose(actual, expected, 0.0, name);
    }
    EXPECT_EQ(differing, 0u) << name << ": pixels that differ";
}

RenderSettings small(const Scene& scene) {
    RenderSettings s = scene.render;
    s.width = 48;
    s.height = 36;
    s.photons = 20001;  // not a multiple of the devices
    s.deterministic = true;
    return s;
}

TEST(Devices, SeveralCpuDevicesRenderOneDevicesImage) {
    for (const char* name : {"cornell.json", "sky.json", "caustic.json"}) {
        Scene scene = loadSceneFile(test::scenesDir() + "/" + name);
        for (Estimator estimator : {Estimator::Sppm, Estimator::Knn}) {
            RenderSettings s = small(scene);
            s.estimator = estimator;
            Rendered one = renderOn("cpu", scene, s, 3);
            for (const char* backends : {"cpu,cpu", "cpu,cpu,cpu"}) {
                SCOPED_TRACE(std::string(name) + " " + toString(estimator) + " on " + backends);
                Rendered several = renderOn(backends, scene, s, 3);
                expectIdentical(several.image, one.image, std::string("devices-") + name + "-" + backends);
                for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
                    EXPECT_EQ(one.last.stored[m], several.last.stored[m]) << kMapNames[m];
                }
                EXPECT_EQ(one.last.environmentPaths, several.last.environmentPaths);
                EXPECT_EQ(one.last.environmentHits, several.last.environmentHits);
                EXPECT_GT(several.last.exchange.bytes, 0u);
            }
        }
    }
}

// A first frame whose maps are too small drops photons on every device alike and runs again with
// grown maps: the counts the devices send make the first device's map grow as one device's does.
TEST(Devices, AnOverflowingMapGrowsAsOnOneDevice) {
    Scene scene = test::overflowingScene();
    RenderSettings s = test::overflowingSettings(small(scene));
    s.photons = 2000;
    Rendered one = renderOn("cpu", scene, s, 2);
    Rendered two = renderOn("cpu,cpu", scene, s, 2);
    expectIdentical(two.image, one.image, "devices-overflow");
    EXPECT_GT(one.last.capacity[MAP_GLOBAL], 2000u);
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        EXPECT_EQ(one.last.capacity[m], two.last.capacity[m]) << kMapNames[m];
        EXPECT_EQ(one.last.stored[m], two.last.stored[m]) << kMapNames[m];
    }
}

TEST(Devices, TheStatsNameEveryDeviceAndTheExchange) {
    auto renderer = createRenderer("cpu,cpu");
    renderer->setScene(loadSceneFile(test::scenesDir() + "/cornell.json"));
    renderer->setSettings(small(renderer->scene()));
    renderer->renderFrame();
    nlohmann::json j = renderStatsJson(*renderer);
    EXPECT_EQ(j["backend"], "cpu,cpu");
    EXPECT_EQ(j["exchange"]["devices"], 2);
    EXPECT_GT(j["exchange"]["bytes"].get<std::uint64_t>(), 0u);
}

TEST(Devices, BadListsAreRefusedByOption) {
    auto message = [](const std::string& backends, const std::string& device) {
        try {
            DeviceOptions options;
            options.device = device;
            createRenderer(backends, options);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    EXPECT_NE(message("cpu,", "").find("--backend 'cpu,': an empty entry"), std::string::npos);
    EXPECT_NE(message("cpu,gpu", "").find("unknown backend 'gpu'"), std::string::npos);
    EXPECT_NE(message("cpu,cpu", "0").find("--device 0: the CPU backend has no devices to choose from"), std::string::npos);
    EXPECT_NE(message("cuda,cuda,cuda", "0,1").find("--device '0,1': 2 entries for 3 devices"), std::string::npos);
    EXPECT_NE(message("cpu,cpu,cpu,cpu,cpu,cpu,cpu,cpu,cpu,cpu,cpu,cpu,cpu,cpu,cpu,cpu,cpu", "").find("at most 16"),
              std::string::npos);
}

}  // namespace
}  // namespace photon
