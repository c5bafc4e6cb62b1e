// The CUDA backend against the CPU reference. The parity build (no FMA contraction) must give the
// same photon maps and hit points bit for bit; both builds must give images within 0.5% relative
// RMSE. Skipped where no CUDA device exists (CI); run on the GPU machine.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/render/devices.h"
#include "backend_compare.h"
#include "core/loaders/scene_loader.h"
#include "core/scene/camera_path.h"
#include "cuda/cuda_device.h"
#include "media_scenes.h"

namespace photon {
namespace {

class CudaVsCpu : public ::testing::Test {
protected:
    void SetUp() override {
        if (cudaDeviceCount() == 0) {
            GTEST_SKIP() << "no CUDA device on this machine";
        }
    }

    // Exhaustive gathers: subsampling a dense cell picks photons by their place in the cell, and
    // the GPU appends photons in a different order than the CPU (see GatherBudget tests).
    static RenderSettings small() {
        RenderSettings s = test::sizedSettings(defaultScene().render, 96, 72, 50000);
        s.frames = 2;
        s.gatherBudget = 0;
        return s;
    }

    // `fastTolerance`: the relative RMSE the fast build may differ by (its fast math moves photons
    // across the edges of estimates' discs).
    void compare(const Scene& scene, const RenderSettings& settings, const std::string& name, bool parity,
                 double fastTolerance = 5e-3) {
        auto cpu = createRenderer("cpu");
        DeviceOptions options;
        options.parity = parity;
        auto cuda = createRenderer("cuda", options);
        test::StageOutputs expected = test::renderStages(*cpu, scene, settings);
        test::StageOutputs actual = test::renderStages(*cuda, scene, settings);
        if (parity) {
            test::expectSamePhotonMaps(actual.maps, expected.maps);
            test::expectSameHitPoints(actual.hitPoints, expected.hitPoints);
        }
        test::expectImagesClose(actual.frame, expected.frame, parity ? 1e-4 : fastTolerance, name + "-frame");
        test::expectImagesClose(actual.image, expected.image, parity ? 1e-4 : fastTolerance, name + "-image");
    }
};

TEST_F(CudaVsCpu, EveryEstimatorAndGridInTheParityBuild) {
    Scene scene = defaultScene();
    for (Estimator e : {Estimator::Cell, Estimator::Radius, Estimator::Knn, Estimator::Progressive, Estimator::Sppm}) {
        for (GridKind g : {GridKind::Hashed, GridKind::Bounded}) {
            RenderSettings s = small();
            s.estimator = e;
            s.grid = g;
            SCOPED_TRACE(std::string(toString(e)) + " " + toString(g));
            compare(scene, s, std::string("cuda-parity-") + toString(e) + "-" + toString(g), true);
        }
    }
}

// The auxiliary images and the denoiser in the parity build: the AOVs equal the CPU's up to the
// rounding of luminance and normals, and the denoised image agrees as the images do.
TEST_F(CudaVsCpu, AovsAndTheDenoiserInTheParityBuild) {
    Scene scene = defaultScene();
    RenderSettings s = small();
    s.estimator = Estimator::Sppm;
    s.denoise = Denoise::On;
    auto cpu = createRenderer("cpu");
    DeviceOptions options;
    options.parity = true;
    auto cuda = createRenderer("cuda", options);
    for (Renderer* b : {cpu.get(), cuda.get()}) {
        b->setScene(scene);
        b->setSettings(s);
        for (int f = 0; f < 5; ++f) {
            b->renderFrame();
        }
    }
    std::vector<PixelAov> a = cpu->readAovs();
    std::vector<PixelAov> b = cuda->readAovs();
    ASSERT_EQ(a.size(), b.size());
    float worst = test::largestAovDifference(a, b);
    std::printf("AOVs: largest difference %.3g\n", worst);
    EXPECT_LE(worst, 1e-5f);
    test::expectImagesClose(cuda->image(), cpu->image(), 1e-4, "cuda-parity-denoised");
    test::expectImagesClose(cuda->rawImage(), cpu->rawImage(), 1e-4, "cuda-parity-raw");
}

// A camera moving along an orbit: the carried histories and the images, as the CPU's.
TEST_F(CudaVsCpu, ReprojectionInTheParityBuild) {
    Scene scene = defaultScene();
    RenderSettings s = small();
    s.estimator = Estimator::Sppm;
    s.denoise = Denoise::On;
    s.reproject = true;
    auto cpu = createRenderer("cpu");
    DeviceOptions options;
    options.parity = true;
    auto cuda = createRenderer("cuda", options);
    const CameraPath orbit{6.0};
    for (Renderer* b : {cpu.get(), cuda.get()}) {
        test::renderFrames(*b, scene, s, 4);
        test::renderAlongPath(*b, orbit, scene.camera, 3);
    }
    std::vector<PixelAov> a = cpu->readAovs();
    std::vector<PixelAov> b = cuda->readAovs();
    ASSERT_EQ(a.size(), b.size());
    std::size_t carried = 0;
    for (const PixelAov& p : a) {
        carried += p.frames > 1.0f ? 1 : 0;
    }
    float worst = test::largestAovDifference(a, b);
    std::printf("reprojection: %zu of %zu pixels carried; AOVs' largest difference %.3g\n", carried, a.size(), worst);
    EXPECT_GT(carried, a.size() / 2);
    EXPECT_LE(worst, 1e-5f);
    test::expectImagesClose(cuda->image(), cpu->image(), 1e-4, "cuda-parity-reprojected-denoised");
    test::expectImagesClose(cuda->rawImage(), cpu->rawImage(), 1e-4, "cuda-parity-reprojected-raw");
}

// The environment (the sky's map, and the studio environment of a model file without lights):
// photons from the bounding box's faces and shadow rays by MIS, bit for bit in the parity build.
// The fast build within 1%: the sky's glass balls split their eye paths, and each branch's
// estimate of 64 photons (eye_trace.h) has the edges fast math moves photons across (0.77% on the
// H100, session 14; 0.5% before the split).
TEST_F(CudaVsCpu, EnvironmentScenesInTheParityBuild) {
    for (const char* file : {"sky.json", "bunny.obj"}) {
        SCOPED_TRACE(file);
        Scene scene = loadSceneFile(test::scenesDir() + "/" + file);
        compare(scene, small(), std::string("cuda-parity-") + file, true);
        compare(scene, small(), std::string("cuda-fast-") + file, false, 1e-2);
    }
}

// Spectral rendering, and a dispersive prism whose paths keep one wavelength each: bit for bit in
// the parity build, within 0.5% in the fast one.
TEST_F(CudaVsCpu, SpectralInTheParityBuild) {
    test::forSpectralCases(defaultScene(), small(), [&](const Scene& scene, const RenderSettings& s) {
        SCOPED_TRACE(scene.name + " " + toString(s.estimator));
        compare(scene, s, std::string("cuda-parity-spectral-") + toString(s.estimator), true);
        compare(scene, s, std::string("cuda-fast-spectral-") + toString(s.estimator), false);
    });
}

// With deterministic photon maps the parity build equals the CPU in order too, so that even
// subsampled gathers (the default gather budget) agree bit for bit.
TEST_F(CudaVsCpu, DeterministicMapsEqualTheCpuInOrder) {
    Scene scene = defaultScene();
    RenderSettings s = small();
    s.gatherBudget = 32;
    s.deterministic = true;
    auto cpu = createRenderer("cpu");
    auto cuda = createRenderer("cuda", DeviceOptions{"", false, true});
    test::StageOutputs expected = test::renderStages(*cpu, scene, s);
    test::StageOutputs actual = test::renderStages(*cuda, scene, s);
    test::expectIdenticalPhotonMaps(actual.maps, expected.maps);
    test::expectSameHitPoints(actual.hitPoints, expected.hitPoints);
    test::expectImagesClose(actual.image, expected.image, 1e-6, "cuda-deterministic");
}

// The same seed twice gives the same image bit for bit (the fast build, deterministic maps).
TEST_F(CudaVsCpu, SameSeedSameImageWhenDeterministic) {
    Scene scene = defaultScene();
    RenderSettings s = small();
    s.gatherBudget = 32;
    s.deterministic = true;
    s.frames = 3;
    Image first = test::renderStages(*createRenderer("cuda"), scene, s).image;
    Image second = test::renderStages(*createRenderer("cuda"), scene, s).image;
    EXPECT_EQ(test::differingPixels(first, second), 0u);
}

// A request larger than this device's memory (derived from the device, so that it fails on any
// GPU) is refused before any work; the backend renders a small one afterwards.
TEST_F(CudaVsCpu, TooLargeRequestsAreRefusedBeforeWork) {
    Scene scene = defaultScene();
    auto cuda = createRenderer("cuda");
    MemoryLimits limits = cuda->memoryLimits();
    RenderSettings s = test::roomFor64PhotonsPerPath(scene.render);
    // Photon buffers alone: the photon pass's records, the maps and a key per stored photon.
    double perPath = 64.0 * (sizeof(Photon) + sizeof(MapPhoton) + sizeof(std::uint32_t));
    double paths = std::ceil(1.5 * double(limits.total) / perPath);
    if (paths > double(PHOTON_PATHS_MAX)) {
        GTEST_SKIP() << limits.device << " has more memory than the largest request can use";
    }
    s.photons = static_cast<std::uint32_t>(paths);
    cuda->setScene(scene);
    cuda->setSettings(s);
    test::expectRefused(*cuda, std::to_string(s.photons) + " photon paths at 64 photons each were accepted");
    cuda->setSettings(test::sizedSettings(scene.render, 64, 48, 10000));
    cuda->renderFrame();
    EXPECT_TRUE(allFinite(cuda->image()));
}

TEST_F(CudaVsCpu, FinalGatherInTheParityBuild) {
    RenderSettings s = small();
    s.globalMode = GlobalMode::FinalGather;
    s.gatherRays = 8;
    compare(defaultScene(), s, "cuda-parity-final-gather", true);
}

TEST_F(CudaVsCpu, FastBuildImagesWithinHalfAPercent) {
    RenderSettings s = small();
    s.photons = 200000;
    s.frames = 4;
    s.estimator = Estimator::Progressive;
    compare(defaultScene(), s, "cuda-fast", false);
}

TEST_F(CudaVsCpu, EveryShippedSceneRendersWithoutNaN) {
    for (const std::string& path : test::shippedScenes({".json", ".glb"})) {
        SCOPED_TRACE(path);
        Scene scene = loadSceneFile(path);
        auto cuda = createRenderer("cuda");
        test::renderFrames(*cuda, scene, test::sizedSettings(scene.render, 64, 48, 20000), 1);
        EXPECT_TRUE(allFinite(cuda->image()));
    }
}

// Meshes through the BVH, textures, smooth normals, emissive triangles and directional light: the
// parity build traverses exactly as the CPU does.
TEST_F(CudaVsCpu, MeshScenesInTheParityBuild) {
    for (const char* file : {"bunny.json", "textured.glb"}) {
        Scene scene = loadSceneFile(test::scenesDir() + "/" + file);
        RenderSettings s = small();
        s.photons = 30000;
        compare(scene, s, std::string("cuda-parity-") + file, true);
    }
}

// Participating media: free flights, the volume map and the beam estimate, bit for bit in the
// parity build, within 0.5% in the fast one. The maps are deterministic: the beam estimate sums a
// cell's photons in their order, which the hit points' light would otherwise show.
TEST_F(CudaVsCpu, MediaInTheParityBuild) {
    Scene scene = loadSceneFile(test::scenesDir() + "/fog.json");
    RenderSettings s = small();
    s.photons = 30000;
    s.deterministic = true;
    compare(scene, s, "cuda-parity-fog", true);
    compare(scene, s, "cuda-fast-fog", false);
}

// A heterogeneous medium: the walks over its voxels, bit for bit in the parity build.
TEST_F(CudaVsCpu, HeterogeneousMediaInTheParityBuild) {
    RenderSettings s = small();
    s.photons = 30000;
    s.deterministic = true;
    compare(test::heterogeneousFog(), s, "cuda-parity-smoky-fog", true);
    compare(test::heterogeneousFog(), s, "cuda-fast-smoky-fog", false);
}

TEST_F(CudaVsCpu, OverflowingPhotonMapGrowsAndTheFirstFrameIsRedone) {
    Scene scene = test::overflowingScene();
    RenderSettings s = test::overflowingSettings(test::sizedSettings({}, 32, 32, 20000));
    auto cuda = createRenderer("cuda", DeviceOptions{"", false, true});
    auto cpu = createRenderer("cpu");
    test::StageOutputs actual = test::renderStages(*cuda, scene, s);
    test::StageOutputs expected = test::renderStages(*cpu, scene, s);
    EXPECT_LE(actual.stats.stored[MAP_GLOBAL], actual.stats.capacity[MAP_GLOBAL]);
    test::expectSamePhotonMaps(actual.maps, expected.maps);
}

// Two CUDA devices (here both on GPU 0 where there is one: two streams and buffer sets) split a
// frame's photon paths and meet in the first one's maps: one device's image and maps, bit for bit,
// also when the maps overflow and grow.
TEST_F(CudaVsCpu, SeveralDevicesRenderOneDevicesImage) {
    DeviceOptions options;
    options.parity = true;
    options.device = "0";
    RenderSettings s = small();
    s.deterministic = true;
    auto one = createRenderer("cuda", options);
    auto two = createRenderer("cuda,cuda", options);
    for (bool overflowing : {false, true}) {
        Scene scene = overflowing ? test::overflowingScene() : defaultScene();
        RenderSettings settings = overflowing ? test::overflowingSettings(s) : s;
        test::StageOutputs expected = test::renderStages(*one, scene, settings);
        test::StageOutputs actual = test::renderStages(*two, scene, settings);
        EXPECT_GT(two->lastFrameStats().exchange.bytes, 0u);
        EXPECT_EQ(test::differingPixels(actual.image, expected.image), 0u) << (overflowing ? "overflowing" : "cornell");
        test::expectIdenticalPhotonMaps(actual.maps, expected.maps);
    }
}

}  // namespace
}  // namespace photon
