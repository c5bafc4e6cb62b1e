// What core decides for every backend about a frame's stages and buffers: the stage list's names
// (the report keys documents and scripts read), the order a frame runs them in, the buffer
// helpers the backends allocate and upload through, the photons a frame by default, and the share
// of them that pixels gather.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "core/frame/scene_settings.h"
#include "core/frame/renderer.h"
#include "core/frame/buffers.h"
#include "core/frame/median.h"
#include "core/frame/photon_use.h"
#include "core/loaders/scene_loader.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "core/render/devices.h"

namespace photon {
namespace {

TEST(StageList, NamesAreTheReportKeys) {
    std::vector<std::string> names;
    for (const StageInfo& s : kStages) {
        names.push_back(s.name);
    }
    EXPECT_EQ(names, (std::vector<std::string>{"tracePhotons", "buildGrid", "tracePixels", "reproject", "gather", "accumulate", "denoise"}));
}

TEST(StageList, EveryStageIsTimed) {
    std::unique_ptr<Renderer> cpu = createRenderer("cpu");
    cpu->setScene(defaultScene());
    RenderSettings s;
    s.width = 32;
    s.height = 24;
    s.photons = 2000;
    cpu->setSettings(s);
    cpu->renderFrame();
    const StageTimes& t = cpu->lastFrameStats().ms;
    double sum = 0.0;
    for (const StageInfo& stage : kStages) {
        EXPECT_GE(t[stage.id], 0.0) << stage.name;
        sum += t[stage.id];
    }
    EXPECT_EQ(t.total(), sum);
}

TEST(Median, OddEvenEmpty) {
    EXPECT_EQ(median({3.0, 1.0, 2.0}), 2.0);
    EXPECT_EQ(median({4.0, 1.0, 2.0, 3.0}), 2.5);
    EXPECT_EQ(median({}), 0.0);
}

// Every changed buffer is freed before any is allocated; unchanged ones and the scene's are left.
TEST(BufferHelpers, ResizeFreesAllChangedBeforeAllocating) {
    BufferPlan plan;
    plan.elements[BINDING_PHOTONS] = 10;
    plan.elements[BINDING_FRAME] = 4;
    plan.elements[BINDING_ACCUMULATION] = 4;
    std::map<std::uint32_t, std::uint64_t> held = {{BINDING_PHOTONS, 0}, {BINDING_FRAME, plan.bytes(BINDING_FRAME)},
                                                   {BINDING_ACCUMULATION, 1}};
    std::vector<std::pair<std::uint32_t, std::uint64_t>> calls;
    resizeChangedBuffers(
        plan, [&](std::uint32_t b, std::uint64_t bytes) { return held[b] == bytes; },
        [&](std::uint32_t b, std::uint64_t bytes) { calls.push_back({b, bytes}); });
    bool allocating = false;
    for (const auto& [binding, bytes] : calls) {
        EXPECT_NE(binding, BINDING_FRAME);
        EXPECT_NE(bufferInfo(binding).size, BUFFER_PER_SCENE);
        EXPECT_TRUE(bytes > 0 || !allocating) << "a buffer was freed after another was allocated";
        allocating = allocating || bytes > 0;
    }
    EXPECT_EQ(calls.size(), 4u);  // photons and accumulation, freed then allocated
}

// A scene array goes up as it is; an empty one as one zeroed element.
TEST(BufferHelpers, SceneBuffersArePaddedToThePlan) {
    Scene scene = defaultScene();
    scene.targets.clear();
    PhotonBudget budget = planPhotons(scene, RenderSettings{});
    BufferPlan plan = planBuffers(scene, budget, 8, 8);
    std::uint32_t seen = 0;
    forEachSceneBuffer(scene, plan, [&](std::uint32_t binding, const void* data, std::uint64_t bytes) {
        seen += 1;
        EXPECT_EQ(bufferInfo(binding).size, BUFFER_PER_SCENE);
        EXPECT_EQ(bytes, plan.bytes(binding));
        HostArray array = sceneArray(scene, binding);
        if (array.count == 0) {
            std::vector<unsigned char> zeros(bytes, 0);
            EXPECT_EQ(std::memcmp(data, zeros.data(), bytes), 0) << bufferInfo(binding).name;
        } else {
            EXPECT_EQ(std::memcmp(data, array.data, bytes), 0) << bufferInfo(binding).name;
        }
    });
    std::uint32_t sceneRows = 0;
    for (const BufferInfo& info : kBuffers) {
        sceneRows += info.size == BUFFER_PER_SCENE ? 1u : 0u;
    }
    EXPECT_EQ(seen, sceneRows);
}

// Photons a frame follow the processor unless the file or the command line gives them: a GPU gets
// kGpuDefaultPhotons, the host's cores one per kCpuPixelsPerPhoton pixels within their bounds.
// A refusal names what shrinks the buffer: the media's density voxels by their grids' resolution,
// not "simplify the scene" (issue 57: lavapipe and a 512³ grid).
TEST(BufferHelpers, RefusalsNameWhatToLower) {
    BufferPlan plan;
    plan.elements[BINDING_PARAMS] = 1;
    plan.elements[BINDING_DENSITIES] = std::uint64_t(512) * 512 * 512;
    plan.elements[BINDING_TRIANGLES] = 1;
    MemoryLimits limits{"llvmpipe", "device memory", std::uint64_t(1) << 40, std::uint64_t(128) << 20, "maxStorageBufferRange"};
    auto messageOf = [&] {
        try {
            checkMemory(plan, limits, 64, 48);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(messageOf().find("buffer 'densities' needs 512.0 MiB"), std::string::npos) << messageOf();
    EXPECT_NE(messageOf().find("lower the density grids' resolution"), std::string::npos) << messageOf();
    plan.elements[BINDING_DENSITIES] = 1;
    plan.elements[BINDING_TRIANGLES] = std::uint64_t(64) << 20;
    EXPECT_NE(messageOf().find("simplify the scene"), std::string::npos) << messageOf();
    limits.perBuffer = 0;
    limits.total = std::uint64_t(1) << 30;
    plan.elements[BINDING_TRIANGLES] = 1;
    plan.elements[BINDING_DENSITIES] = std::uint64_t(1) << 30;
    EXPECT_NE(messageOf().find("the largest is 'densities'"), std::string::npos) << messageOf();
    EXPECT_NE(messageOf().find("lower the density grids' resolution"), std::string::npos) << messageOf();
}

TEST(DefaultPhotons, FollowTheProcessorUnlessGiven) {
    Scene scene = defaultScene();
    EXPECT_FALSE(isGiven(scene.render, "photons")) << "the shipped Cornell box leaves the count to the backend";
    RenderSettings s = scene.render;
    s.width = 640;
    s.height = 480;
    RenderSettings gpu = s;
    choosePhotons(gpu, false);
    EXPECT_EQ(gpu.photons, kGpuDefaultPhotons);
    RenderSettings cpu = s;
    choosePhotons(cpu, true);
    EXPECT_EQ(cpu.photons, 102000u);
    cpu.width = 64;
    cpu.height = 48;
    choosePhotons(cpu, true);
    EXPECT_EQ(cpu.photons, kCpuPhotonsMin);
    cpu.width = 3840;
    cpu.height = 2160;
    choosePhotons(cpu, true);
    EXPECT_EQ(cpu.photons, kGpuDefaultPhotons) << "never more than a GPU's";
    RenderSettings given = s;
    setSetting(given, *findSetting("photons"), "300000", "--photons");
    choosePhotons(given, true);
    EXPECT_EQ(given.photons, 300000u);
    Scene file = loadSceneJson(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 40},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"}],
        "materials": {"white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
        "lights": [{"type": "point", "position": [0, 3, 0], "power": [1, 1, 1]}],
        "render": {"photons": 70000}})", "inline.json", "", defaultFileReader());
    RenderSettings fromFile = file.render;
    choosePhotons(fromFile, false);
    EXPECT_EQ(fromFile.photons, 70000u);
}

// Spectral rendering comes on by itself for a scene with a dispersive material, unless the file or
// the command line says otherwise; RGB elsewhere.
TEST(DefaultSpectral, OnWhereAMaterialDisperses) {
    auto sceneWith = [](const char* glass, const char* render) {
        return loadSceneJson(std::string(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 40},
            "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glass"}],
            "materials": {"glass": )") + glass + R"(},
            "lights": [{"type": "point", "position": [0, 3, 0], "power": [1, 1, 1]}], "render": )" + render + "}",
                             "inline.json", "", defaultFileReader());
    };
    Scene plain = sceneWith(R"({"type": "glass", "ior": 1.5})", "{}");
    Scene flint = sceneWith(R"({"type": "glass", "ior": 1.6, "abbe": 30})", "{}");
    Scene flintRgb = sceneWith(R"({"type": "glass", "ior": 1.6, "abbe": 30})", R"({"spectral": false})");
    for (auto [scene, expected] : {std::pair{&plain, false}, {&flint, true}, {&flintRgb, false}}) {
        RenderSettings s = scene->render;
        chooseSpectral(s, *scene);
        EXPECT_EQ(s.spectral, expected) << scene->materials.size();
    }
    RenderSettings given = flint.render;
    setSetting(given, *findSetting("spectral"), "false", "--spectral");
    chooseSpectral(given, flint);
    EXPECT_FALSE(given.spectral);
}

// In the closed box nearly every global photon lands where a pixel sees; through a narrow lens that
// sees a patch of the back wall, few do. The measure counts each photon once, whatever the discs.
TEST(PhotonUse, FollowsWhatTheCameraSees) {
    double share[2];
    for (int narrow = 0; narrow < 2; ++narrow) {
        Scene scene = defaultScene();
        if (narrow == 1) {
            scene.camera.fovY = 4.0f;
        }
        RenderSettings s = scene.render;
        s.width = 64;
        s.height = 48;
        s.photons = 40000;
        s.estimator = Estimator::Sppm;
        std::unique_ptr<Renderer> backend = createRenderer("cpu");
        backend->setScene(scene);
        backend->setSettings(s);
        for (int f = 0; f < 2; ++f) {
            backend->renderFrame();
        }
        PhotonUse use = measurePhotonUse(*backend);
        ASSERT_GT(use.stored[MAP_GLOBAL], 1000u);
        EXPECT_LE(use.gathered[MAP_GLOBAL], use.stored[MAP_GLOBAL]);
        if (narrow == 1) {
            EXPECT_EQ(use.discs[MAP_GLOBAL], 64u * 48u) << "every pixel sees the back wall";
        } else {
            EXPECT_GT(use.discs[MAP_GLOBAL], 64u * 48u / 2u) << "most pixels see the box";
        }
        share[narrow] = double(use.gathered[MAP_GLOBAL]) / double(use.stored[MAP_GLOBAL]);
    }
    std::printf("global photons gathered: %.3f of the box, %.3f through a 4-degree lens\n", share[0], share[1]);
    EXPECT_GT(share[0], 0.8);
    EXPECT_LT(share[1], 0.1);
}

}  // namespace
}  // namespace photon
