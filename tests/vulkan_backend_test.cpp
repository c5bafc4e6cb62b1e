// The Vulkan backend against the CPU reference, stage by stage, on the same scenes and settings,
// with the validation layer on (any message it prints fails the test):
//   photon pass + grid build: each map's cellStart identical, and each cell holding the same
//                             photons bit for bit (in any order: appends race on the GPU);
//   eye pass:                 hit points bit-identical;
//   estimates, running mean:  images within a relative RMSE (measured and printed), for every
//                             estimator, both grids and final gather.
// Also: every scene in scenes/ renders finite, too-large requests are refused before any work,
// and a photon map that overflows is grown without losing photons.
// Bit-exactness is asserted on lavapipe, which the file picks when it is installed (its arithmetic
// is g++'s: IEEE, no contraction). Other drivers contract FMAs and approximate division, so some
// photon paths take other turns and the images differ by noise: there the images must agree within
// 1.5× the difference between two CPU renders with different seeds. Skipped when no Vulkan device exists. Building the pipelines costs
// seconds of LLVM time on lavapipe (less with Mesa's shader cache), so one backend serves the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/render/devices.h"
#include "backend_compare.h"
#include "core/loaders/scene_loader.h"
#include "core/scene/camera_path.h"
#include "core/system/error.h"
#include "shared/photon_map.h"
#include "media_scenes.h"
#include "test_util.h"
#include "vulkan/context.h"
#include "vulkan/vulkan_device.h"

namespace photon {
namespace {

// A scene with every primitive, material and light type: planes, triangles, glossy and
// mirror-coated surfaces, point, hemisphere, spot, sphere and quad lights, and a thin lens.
Scene featureScene() {
    Scene s;
    s.name = "feature mix";
    std::uint32_t white = s.addMaterial("white", makeDiffuse(glm::vec3(0.7f)));
    std::uint32_t green = s.addMaterial("green", makeDiffuse(glm::vec3(0.2f, 0.6f, 0.2f)));
    std::uint32_t glossy = s.addMaterial("glossy", makeGlossy(glm::vec3(0.3f, 0.3f, 0.6f), glm::vec3(0.5f), 0.2f));
    std::uint32_t coated = s.addMaterial("coated", makeReflective(glm::vec3(0.5f, 0.3f, 0.2f), glm::vec3(0.3f)));
    std::uint32_t glass = s.addMaterial("glass", makeGlass(1.5f, glm::vec3(0.95f)));
    std::uint32_t mirror = s.addMaterial("mirror", makeMirror(glm::vec3(0.9f)));
    s.addPlane(glm::vec3(0, 0, 0), glm::vec3(0, 1, 0), coated);
    s.addPlane(glm::vec3(0, 0, -2), glm::vec3(0, 0, 1), white);
    s.addQuad(glm::vec3(-2, 0, -2), glm::vec3(0, 3, 0), glm::vec3(0, 0, 4), green);
    s.addQuad(glm::vec3(-2, 3, -2), glm::vec3(4, 0, 0), glm::vec3(0, 0, 4), white);
    s.addTriangle(glm::vec3(0.5f, 0, -1), glm::vec3(1.5f, 0, -0.5f), glm::vec3(1.0f, 1.2f, -0.8f), glossy);
    s.addTriangle(glm::vec3(1.5f, 0, -0.5f), glm::vec3(1.2f, 0, 0.3f), glm::vec3(1.0f, 1.2f, -0.8f), glossy);
    s.addSphere(glm::vec3(-0.6f, 0.5f, 0.2f), 0.5f, glass);
    s.addSphere(glm::vec3(0.4f, 0.35f, 0.6f), 0.35f, mirror);
    s.addSphere(glm::vec3(-1.2f, 1.6f, -1.2f), 0.3f, glossy);
    s.addPointLight(glm::vec3(0.8f, 2.5f, 0.5f), glm::vec3(4.0f));
    s.addHemisphereLight(glm::vec3(0, 2.95f, 0), glm::vec3(0, -1, 0), glm::vec3(6.0f));
    s.addSpotLight(glm::vec3(1.8f, 2.0f, 1.5f), glm::vec3(-1, -1, -1), glm::vec3(5.0f), 30.0f, 20.0f);
    s.addSphereLight(glm::vec3(-1.5f, 2.4f, 1.0f), 0.15f, glm::vec3(3.0f));
    s.addQuadLight(glm::vec3(-0.3f, 2.99f, -1.5f), glm::vec3(0.6f, 0, 0), glm::vec3(0, 0, 0.4f), glm::vec3(3.0f));
    s.camera.position = glm::vec3(0.2f, 1.3f, 4.0f);
    s.camera.lookAt = glm::vec3(0.0f, 0.8f, 0.0f);
    s.camera.fovY = 50.0f;
    s.camera.lensRadius = 0.02f;
    s.finalize();
    return s;
}

// Small images and photon counts, so that the whole file runs in seconds on lavapipe. Queries
// visit every photon of a cell (gather budget 0): a subsampled cell depends on the order of its
// photons, which on a GPU is the order in which atomics happened to append them.
RenderSettings smallSettings(std::uint32_t photons = 40000) {
    RenderSettings s = test::sizedSettings({}, 48, 36, photons);
    s.radius = 0.08f;
    s.causticRadius = 0.05f;
    s.gatherBudget = 0;
    return s;
}

// Relative RMSE of the Vulkan image against the CPU's; prints it with the count of pixels that are
// not bit-identical.
double compareImages(const Image& cpu, const Image& vulkan, const std::string& what) {
    EXPECT_EQ(cpu.pixels.size(), vulkan.pixels.size()) << what;
    EXPECT_TRUE(allFinite(vulkan)) << what;
    double error = relativeRmse(vulkan, cpu);
    std::printf("%s: relative RMSE %.3g, %zu of %zu pixels not bit-identical\n", what.c_str(), error,
                test::differingPixels(cpu, vulkan), cpu.pixels.size());
    return error;
}

class VulkanBackendTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        if (vulkanDeviceCount() == 0) {
            return;
        }
        DeviceOptions options;
        options.validation = true;
        options.device = "llvmpipe";
        try {
            vulkan_ = createRenderer("vulkan", options).release();
            lavapipe_ = true;
        } catch (const RuntimeError&) {
            options.device = "";
            vulkan_ = createRenderer("vulkan", options).release();
        }
        cpu_ = createRenderer("cpu").release();
        otherSeed_ = createRenderer("cpu").release();
        std::printf("Vulkan device: %s\n", vulkan_->deviceName().c_str());
    }

    static void TearDownTestSuite() {
        delete vulkan_;
        delete cpu_;
        delete otherSeed_;
        vulkan_ = nullptr;
        cpu_ = nullptr;
        otherSeed_ = nullptr;
    }

    void SetUp() override {
        if (vulkan_ == nullptr) {
            GTEST_SKIP() << "no Vulkan device: vulkanDeviceCount() == 0";
        }
    }

    // Relative RMSE allowed between the Vulkan and CPU images. On lavapipe only the order of the
    // photons within a cell differs (atomic appends), so sums round differently: measured ≤ 1e-7.
    // Elsewhere: the noise of the last render() (see the file comment).
    static double imageTolerance() { return lavapipe_ ? 1e-5 : std::max(0.005, 1.5 * noise_); }

    // Photon maps and hit points bit for bit, where the arithmetic is the CPU's.
    static void expectSameStages(const std::string& what, bool maps = true, bool hitPoints = true) {
        if (!lavapipe_) {
            std::printf("%s: not lavapipe, bit-exact stages not compared\n", what.c_str());
            return;
        }
        SCOPED_TRACE(what);
        if (maps) {
            test::expectSamePhotonMaps(vulkan_->readPhotonMaps(), cpu_->readPhotonMaps());
        }
        if (hitPoints) {
            test::expectSameHitPoints(vulkan_->readHitPoints(), cpu_->readHitPoints());
        }
    }

    // Both backends render `frames` frames of the scene (and, off lavapipe, the CPU again with
    // another seed, to measure the noise).
    static void render(const Scene& scene, const RenderSettings& settings, std::uint32_t frames = 1) {
        RenderSettings other = settings;
        other.seed += 1000;
        for (auto [b, s] : {std::pair{cpu_, settings}, {vulkan_, settings}, {otherSeed_, other}}) {
            if (b == otherSeed_ && lavapipe_) {
                continue;
            }
            b->setScene(scene);
            b->setSettings(s);
            for (std::uint32_t f = 0; f < frames; ++f) {
                b->renderFrame();
            }
        }
        if (!lavapipe_) {
            noise_ = std::max(relativeRmse(otherSeed_->readFrame(), cpu_->readFrame()),
                              relativeRmse(otherSeed_->image(), cpu_->image()));
        }
    }

    // A shipped scene file, one frame of 20000 photons: the stages bit for bit, the frames close.
    static void renderSceneFileAndCompare(const char* file) {
        Scene scene = loadSceneFile(test::scenesDir() + "/" + file);
        RenderSettings settings = smallSettings();
        settings.photons = 20000;
        render(scene, settings);
        expectSameStages(file, true, true);
        EXPECT_LE(compareImages(cpu_->readFrame(), vulkan_->readFrame(), file), imageTolerance());
    }

    static Renderer* vulkan_;
    static Renderer* cpu_;
    static Renderer* otherSeed_;  // the CPU with another seed: the noise to allow off lavapipe
    static double noise_;
    static bool lavapipe_;  // the device is lavapipe: photon maps and hit points bit-exact
};

Renderer* VulkanBackendTest::vulkan_ = nullptr;
Renderer* VulkanBackendTest::cpu_ = nullptr;
Renderer* VulkanBackendTest::otherSeed_ = nullptr;
double VulkanBackendTest::noise_ = 0.0;
bool VulkanBackendTest::lavapipe_ = false;

TEST_F(VulkanBackendTest, PhotonMapsMatchCpuOnBothGrids) {
    if (!lavapipe_) {
        GTEST_SKIP() << "bit-exact photon maps are compared on lavapipe only (a GPU contracts to FMA)";
    }
    for (GridKind grid : {GridKind::Hashed, GridKind::Bounded}) {
        RenderSettings settings = smallSettings();
        settings.grid = grid;
        settings.gridResolution = 32;
        for (const Scene& scene : {defaultScene(), featureScene()}) {
            render(scene, settings);
            expectSameStages(scene.name + " " + toString(grid), true, false);
        }
    }
}

TEST_F(VulkanBackendTest, HitPointsBitIdentical) {
    if (!lavapipe_) {
        GTEST_SKIP() << "bit-exact hit points are compared on lavapipe only (a GPU contracts to FMA)";
    }
    for (const Scene& scene : {defaultScene(), featureScene()}) {
        render(scene, smallSettings());
        expectSameStages(scene.name, false, true);
    }
}

// The frame's estimates and the running mean for every estimator on both grids, over two frames (the progressive
// radius shrinks in the second).
TEST_F(VulkanBackendTest, EveryEstimatorAndGridAgreesWithCpu) {
    for (Estimator estimator : {Estimator::Cell, Estimator::Radius, Estimator::Knn, Estimator::Progressive, Estimator::Sppm}) {
        for (GridKind grid : {GridKind::Hashed, GridKind::Bounded}) {
            RenderSettings settings = smallSettings();
            settings.estimator = estimator;
            settings.grid = grid;
            settings.gridResolution = 32;
            settings.k = 16;
            render(featureScene(), settings, 2);
            std::string what = std::string(toString(estimator)) + " " + toString(grid);
            EXPECT_LE(compareImages(cpu_->readFrame(), vulkan_->readFrame(), what + " frame"), imageTolerance());
            EXPECT_LE(compareImages(cpu_->image(), vulkan_->image(), what + " mean"), imageTolerance());
        }
    }
}

// The auxiliary images (shared/aov.h) equal the CPU's, up to the rounding of the luminance and the
// normal's decoding; the denoised image agrees as the images do.
TEST_F(VulkanBackendTest, AovsAndTheDenoiserAgreeWithCpu) {
    RenderSettings settings = smallSettings();
    settings.estimator = Estimator::Sppm;
    settings.denoise = Denoise::On;
    render(featureScene(), settings, 5);
    std::vector<PixelAov> a = cpu_->readAovs();
    std::vector<PixelAov> b = vulkan_->readAovs();
    ASSERT_EQ(a.size(), std::size_t(settings.width) * settings.height);
    ASSERT_EQ(a.size(), b.size());
    float worst = test::largestAovDifference(a, b);
    float worstMoment = 0.0f;
    for (std::size_t i = 0; i < a.size(); ++i) {
        worstMoment = std::max(worstMoment, std::abs(a[i].luminance - b[i].luminance) / std::max(a[i].luminance, 1.0f));
    }
    std::printf("AOVs: largest difference %.3g (moments %.3g)\n", worst, worstMoment);
    EXPECT_LE(worst, lavapipe_ ? 1e-5f : 1e-3f);
    EXPECT_LE(worstMoment, lavapipe_ ? 1e-3f : 0.05f);
    EXPECT_LE(compareImages(cpu_->image(), vulkan_->image(), "denoised"), imageTolerance());
    EXPECT_LE(compareImages(cpu_->rawImage(), vulkan_->rawImage(), "raw"), imageTolerance());
}

// A camera that moves along an orbit: each pixel's carried history (its length, depth and normal)
// is the CPU's, and so are the images.
TEST_F(VulkanBackendTest, ReprojectionAgreesWithCpu) {
    RenderSettings settings = smallSettings();
    settings.estimator = Estimator::Sppm;
    settings.denoise = Denoise::On;
    settings.reproject = true;
    Scene scene = featureScene();
    render(scene, settings, 4);
    const CameraPath orbit{6.0};
    for (Renderer* b : {cpu_, vulkan_}) {
        test::renderAlongPath(*b, orbit, scene.camera, 3);
    }
    std::vector<PixelAov> a = cpu_->readAovs();
    std::vector<PixelAov> b = vulkan_->readAovs();
    ASSERT_EQ(a.size(), b.size());
    std::size_t carried = 0;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        carried += a[i].frames > 1.0f ? 1 : 0;
        differing += a[i].frames != b[i].frames ? 1 : 0;
    }
    std::printf("reprojection: %zu of %zu pixels carried a history; %zu history lengths differ\n", carried, a.size(),
                differing);
    EXPECT_GT(carried, a.size() / 2);
    if (lavapipe_) {
        EXPECT_EQ(differing, 0u);
        EXPECT_LE(test::largestAovDifference(a, b), 1e-5f);
    } else {
        EXPECT_LE(differing, a.size() / 100);
    }
    EXPECT_LE(compareImages(cpu_->rawImage(), vulkan_->rawImage(), "reprojected raw"), imageTolerance());
    EXPECT_LE(compareImages(cpu_->image(), vulkan_->image(), "reprojected denoised"), imageTolerance());
}

TEST_F(VulkanBackendTest, FinalGatherAgreesWithCpu) {
    for (Estimator estimator : {Estimator::Radius, Estimator::Knn}) {
        RenderSettings settings = smallSettings();
        settings.globalMode = GlobalMode::FinalGather;
        settings.gatherRays = 4;
        settings.estimator = estimator;
        settings.k = 16;
        for (const Scene& scene : {defaultScene(), featureScene()}) {
            render(scene, settings);
            std::string what = scene.name + " final gather " + toString(estimator);
            EXPECT_LE(compareImages(cpu_->readFrame(), vulkan_->readFrame(), what), imageTolerance());
        }
    }
}

TEST_F(VulkanBackendTest, EveryViewAgreesWithCpu) {
    for (View view : {View::Direct, View::Global, View::Caustic, View::Grid, View::Volume}) {
        RenderSettings settings = smallSettings();
        settings.view = view;
        render(featureScene(), settings);
        EXPECT_LE(compareImages(cpu_->readFrame(), vulkan_->readFrame(), std::string("view ") + toString(view)),
                  imageTolerance());
    }
}

TEST_F(VulkanBackendTest, EverySceneFileRendersFinite) {
    int scenes = 0;
    for (const std::string& path : test::shippedScenes({".json", ".glb"})) {
        Scene scene = loadSceneFile(path);
        RenderSettings settings = test::sizedSettings(scene.render, 40, 30, 30000);
        settings.gatherBudget = 0;  // see smallSettings()
        render(scene, settings, 2);
        Image image = vulkan_->image();
        EXPECT_TRUE(allFinite(image)) << path;
        EXPECT_GT(meanLuminance(image), 0.0) << path;
        EXPECT_LE(compareImages(cpu_->image(), image, std::filesystem::path(path).filename().string()), imageTolerance());
        scenes += 1;
    }
    EXPECT_GT(scenes, 0);
}

// Meshes through the BVH, textures, smooth normals, emissive triangles and directional light: on
// lavapipe the photon maps and hit points equal the CPU's bit for bit.
TEST_F(VulkanBackendTest, MeshScenesMatchCpu) {
    for (const char* file : {"bunny.json", "textured.glb"}) {
        renderSceneFileAndCompare(file);
    }
}

// The environment: the sky scene (a map: its cdf searches and photons from the bounding box's
// faces), and the studio environment of a model file with no lights (bunny.obj on its own): on
// lavapipe the photon maps and hit points equal the CPU's bit for bit.
TEST_F(VulkanBackendTest, EnvironmentScenesMatchCpu) {
    for (const char* file : {"sky.json", "bunny.obj"}) {
        renderSceneFileAndCompare(file);
        EXPECT_GT(vulkan_->lastFrameStats().environmentHits, 0u) << file;
        EXPECT_EQ(vulkan_->lastFrameStats().environmentHits, cpu_->lastFrameStats().environmentHits) << file;
    }
}

// Participating media (the fog-filled box: free flights, the volume map, the beam estimate, shadow
// rays through the fog), in deterministic maps (the beam estimate sums a cell's photons in their
// order). With isotropic fog, on lavapipe the photon maps and hit points equal the CPU's bit for
// bit; with the scene's forward-scattering fog (g = 0.3) lavapipe's Henyey–Greenstein directions
// differ from g++'s in their last bits, so the same photons are stored and the frames agree to
// rounding.
TEST_F(VulkanBackendTest, MediaMatchCpu) {
    Scene scene = loadSceneFile(test::scenesDir() + "/fog.json");
    RenderSettings settings = smallSettings();
    settings.photons = 20000;
    settings.deterministic = true;
    render(scene, settings);
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        EXPECT_EQ(vulkan_->lastFrameStats().stored[m], cpu_->lastFrameStats().stored[m]) << kMapNames[m];
    }
    EXPECT_GT(cpu_->lastFrameStats().stored[MAP_VOLUME], 0u);
    EXPECT_LE(compareImages(cpu_->readFrame(), vulkan_->readFrame(), "fog.json"), lavapipe_ ? 1e-5 : imageTolerance());
    for (Medium& md : scene.media) {
        md.g = 0.0f;
    }
    render(scene, settings);
    expectSameStages("fog.json, isotropic", true, true);
    EXPECT_LE(compareImages(cpu_->readFrame(), vulkan_->readFrame(), "fog.json, isotropic"), imageTolerance());
}

// A heterogeneous medium: walks over its voxels in every flight, shadow ray and beam, bit for bit
// with an isotropic phase function.
TEST_F(VulkanBackendTest, HeterogeneousMediaMatchCpu) {
    Scene scene = test::heterogeneousFog();
    for (Medium& md : scene.media) {
        md.g = 0.0f;
    }
    RenderSettings settings = smallSettings();
    settings.photons = 20000;
    settings.deterministic = true;
    render(scene, settings);
    EXPECT_GT(cpu_->lastFrameStats().stored[MAP_VOLUME], 0u);
    expectSameStages(scene.name, true, true);
    EXPECT_LE(compareImages(cpu_->readFrame(), vulkan_->readFrame(), scene.name), imageTolerance());
}

// Spectral rendering: the frame's wavelengths in every stage, a dispersive prism whose paths keep
// one wavelength each (a draw of their own random numbers): on lavapipe the photon maps and hit
// points equal the CPU's bit for bit, and the images agree.
TEST_F(VulkanBackendTest, SpectralStagesMatchCpu) {
    test::forSpectralCases(featureScene(), smallSettings(), [&](const Scene& scene, const RenderSettings& settings) {
        render(scene, settings, 2);
        std::string what = scene.name + " spectral " + toString(settings.estimator);
        expectSameStages(what);
        EXPECT_LE(compareImages(cpu_->image(), vulkan_->image(), what), imageTolerance());
    });
}

// A map that overflows its capacity in the first frame is grown and the frame runs again, so the
// maps hold every photon: they match the CPU's.
TEST_F(VulkanBackendTest, OverflowingMapGrowsWithoutLosingPhotons) {
    render(test::overflowingScene(), test::overflowingSettings(smallSettings()));
    const FrameStats& stats = vulkan_->lastFrameStats();
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        EXPECT_LE(stats.stored[m], stats.capacity[m]) << "map " << m;
        std::printf("map %u: stored %u, capacity %u after growing\n", m, stats.stored[m], stats.capacity[m]);
    }
    expectSameStages("grown", true, false);
    EXPECT_LE(compareImages(cpu_->readFrame(), vulkan_->readFrame(), "grown"), imageTolerance());
}

// With a gather budget, cells denser than the budget are subsampled from a random start in their
// photon order, which on the GPU is the order of the atomic appends: the image then differs from
// the CPU's (and from run to run) by sampling noise, measured at 0.1–10% relative RMSE here, but
// not in the mean.
TEST_F(VulkanBackendTest, DefaultGatherBudgetAgreesWithinNoise) {
    RenderSettings settings = smallSettings();
    settings.gatherBudget = RenderSettings{}.gatherBudget;
    settings.grid = GridKind::Bounded;
    settings.gridResolution = 16;  // cells of hundreds to thousands of photons: most are subsampled
    for (const Scene& scene : {defaultScene(), featureScene()}) {
        render(scene, settings);
        std::string what = scene.name + " subsampled cells";
        double error = compareImages(cpu_->readFrame(), vulkan_->readFrame(), what);
        double mean = meanLuminance(vulkan_->readFrame()) / meanLuminance(cpu_->readFrame());
        std::printf("%s: mean luminance Vulkan/CPU %.5f\n", what.c_str(), mean);
        EXPECT_TRUE(std::isfinite(error)) << what;
        EXPECT_NEAR(mean, 1.0, 0.02) << what;
    }
}

// Any warning or error of the validation layer reaches the program as a RuntimeError.
TEST_F(VulkanBackendTest, ValidationMessagesBecomeErrors) {
    vk::ContextOptions options;
    options.validation = true;
    vk::Context context(options);
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = 0;  // invalid: VUID-VkBufferCreateInfo-size-00912
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    if (vkCreateBuffer(context.device, &info, nullptr, &buffer) == VK_SUCCESS) {
        vkDestroyBuffer(context.device, buffer, nullptr);
    }
    EXPECT_THROW(context.checkValidation("a test"), RuntimeError);
    EXPECT_NO_THROW(context.checkValidation("a test"));  // each message is reported once
}

// Requests beyond the device's limits are refused with InputError before any work, naming the
// buffer; the backend stays usable.
// Requests beyond this device's limits (derived from the device) are refused before any work.
TEST_F(VulkanBackendTest, TooLargeRequestsAreRefusedBeforeWork) {
    Scene scene = defaultScene();
    MemoryLimits limits = vulkan_->memoryLimits();
    RenderSettings huge = smallSettings();
    // The hit points alone exceed one buffer's range.
    double pixels = std::ceil(1.5 * double(limits.perBuffer) / sizeof(HitPoint));
    huge.width = 16384;
    huge.height = static_cast<std::uint32_t>(std::min(16384.0, std::ceil(pixels / 16384.0)));
    vulkan_->setScene(scene);
    vulkan_->setSettings(huge);
    test::expectRefused(*vulkan_, std::to_string(huge.width) + "x" + std::to_string(huge.height) + " was accepted",
                        "resolution");
    RenderSettings many = test::roomFor64PhotonsPerPath(smallSettings());
    double paths = std::ceil(1.5 * double(limits.perBuffer) / (64.0 * sizeof(Photon)));
    many.photons = static_cast<std::uint32_t>(std::min<double>(paths, PHOTON_PATHS_MAX));
    vulkan_->setSettings(many);
    test::expectRefused(*vulkan_, std::to_string(many.photons) + " photons were accepted", "photon");
    vulkan_->setSettings(smallSettings());
    vulkan_->renderFrame();
    EXPECT_TRUE(allFinite(vulkan_->image()));
}

// Deterministic photon maps: on lavapipe the same photons in the same order as the CPU's, so that
// subsampled gathers agree too; on every device the same seed twice gives the same image bit for bit.
// Radii of a third of the box give cells of thousands of photons: cells of many chunks to merge.
TEST_F(VulkanBackendTest, DeterministicMapsEqualTheCpuInOrder) {
    for (float radius : {0.0f, 1.2f}) {
    for (const Scene& scene : {defaultScene(), featureScene()}) {
        RenderSettings settings = smallSettings();
        settings.gatherBudget = 16;
        settings.deterministic = true;
        if (radius > 0.0f) {
            settings.radius = radius;
            settings.causticRadius = radius;
        }
        render(scene, settings, 2);
        if (radius > 0.0f) {
            GridStats grid = gridStats(vulkan_->readPhotonMaps().cellStart[MAP_GLOBAL]);
            EXPECT_GT(grid.maxPerCell, 2 * ORDER_CHUNK) << scene.name << ": no cell of three chunks";
        }
        if (lavapipe_) {
            // Elsewhere the device's own arithmetic (FMA contraction) moves photons a little.
            test::expectIdenticalPhotonMaps(vulkan_->readPhotonMaps(), cpu_->readPhotonMaps());
            EXPECT_LE(compareImages(cpu_->image(), vulkan_->image(), scene.name + " deterministic"), 1e-6);
        }
        Image first = vulkan_->image();
        render(scene, settings, 2);
        EXPECT_EQ(test::differingPixels(first, vulkan_->image()), 0u) << scene.name << ": the same seed twice";
    }
    }
}

// Two Vulkan devices split a frame's photon paths and the second sends its photons to the first
// (core/frame/collective.h): the image is one device's bit for bit. On one GPU (or lavapipe) the
// two devices are two contexts on it; the exchange goes through writeBuffer's upload at an offset.
TEST_F(VulkanBackendTest, TwoDevicesRenderOneDevicesImage) {
    DeviceOptions options;
    options.validation = true;
    options.device = lavapipe_ ? "llvmpipe" : "";
    auto two = createRenderer("vulkan,vulkan", options);
    for (const Scene& scene : {defaultScene(), featureScene()}) {
        RenderSettings settings = smallSettings();
        settings.deterministic = true;
        render(scene, settings, 2);
        two->setScene(scene);
        two->setSettings(settings);
        two->renderFrame();
        two->renderFrame();
        EXPECT_GT(two->lastFrameStats().exchange.bytes, 0u);
        EXPECT_EQ(test::differingPixels(vulkan_->image(), two->image()), 0u) << scene.name;
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            EXPECT_EQ(vulkan_->lastFrameStats().stored[m], two->lastFrameStats().stored[m]) << kMapNames[m];
        }
    }
}

}  // namespace
}  // namespace photon
