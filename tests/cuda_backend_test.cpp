// The CUDA backend against the CPU reference. The parity build (no FMA contraction) must give the
// same photon maps and hit points bit for bit; both builds must give images within 0.5% relative
// RMSE. Skipped where no CUDA device exists (CI); run on the GPU machine.
#include <gtest/gtest.h>

#include <filesystem>

#include "apps/backends.h"
#include "backend_compare.h"
#include "core/error.h"
#include "core/scene_loader.h"
#include "cuda/cuda_backend.h"

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
        RenderSettings s = defaultScene().render;
        s.width = 96;
        s.height = 72;
        s.photons = 50000;
        s.frames = 2;
        s.gatherBudget = 0;
        return s;
    }

    void compare(const Scene& scene, const RenderSettings& settings, const std::string& name, bool parity) {
        auto cpu = createBackend("cpu");
        BackendOptions options;
        options.parity = parity;
        auto cuda = createBackend("cuda", options);
        test::StageOutputs expected = test::renderStages(*cpu, scene, settings);
        test::StageOutputs actual = test::renderStages(*cuda, scene, settings);
        if (parity) {
            test::expectSamePhotonMaps(actual.maps, expected.maps);
            test::expectSameHitPoints(actual.hitPoints, expected.hitPoints);
        }
        test::expectImagesClose(actual.frame, expected.frame, parity ? 1e-4 : 5e-3, name + "-frame");
        test::expectImagesClose(actual.image, expected.image, parity ? 1e-4 : 5e-3, name + "-image");
    }
};

TEST_F(CudaVsCpu, EveryEstimatorAndGridInTheParityBuild) {
    Scene scene = defaultScene();
    for (Estimator e : {Estimator::Cell, Estimator::Radius, Estimator::Knn, Estimator::Progressive}) {
        for (GridKind g : {GridKind::Hashed, GridKind::Bounded}) {
            RenderSettings s = small();
            s.estimator = e;
            s.grid = g;
            SCOPED_TRACE(std::string(toString(e)) + " " + toString(g));
            compare(scene, s, std::string("cuda-parity-") + toString(e) + "-" + toString(g), true);
        }
    }
}

TEST_F(CudaVsCpu, RadixSortGridMatchesToo) {
    Scene scene = defaultScene();
    RenderSettings s = small();
    auto cpu = createBackend("cpu");
    auto cuda = createBackend("cuda", BackendOptions{"", false, true});
    LaunchConfig radix;
    radix.radixSortGrid = true;
    setCudaLaunchConfig(*cuda, radix);
    test::StageOutputs expected = test::renderStages(*cpu, scene, s);
    test::StageOutputs actual = test::renderStages(*cuda, scene, s);
    test::expectSamePhotonMaps(actual.maps, expected.maps);
    test::expectImagesClose(actual.image, expected.image, 1e-4, "cuda-radix-grid");
}

TEST_F(CudaVsCpu, TooLargeRequestsAreRefusedBeforeWork) {
    Scene scene = defaultScene();
    RenderSettings s = scene.render;
    s.width = 16384;
    s.height = 16384;
    s.photons = 1u << 28;
    s.photonCapacity = 8.0f;  // 1.2G photons and 270M pixels: over 100 GB
    auto cuda = createBackend("cuda");
    cuda->setScene(scene);
    cuda->setSettings(s);
    EXPECT_THROW(cuda->prepare(), InputError);
    s.width = 64;
    s.height = 48;
    s.photons = 10000;
    s.photonCapacity = 4.0f;
    cuda->setSettings(s);
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
    for (const auto& entry : std::filesystem::directory_iterator(test::scenesDir())) {
        if (entry.path().extension() != ".json") {
            continue;
        }
        SCOPED_TRACE(entry.path().string());
        Scene scene = loadSceneFile(entry.path().string());
        RenderSettings s = scene.render;
        s.width = 64;
        s.height = 48;
        s.photons = 20000;
        auto cuda = createBackend("cuda");
        cuda->setScene(scene);
        cuda->setSettings(s);
        cuda->renderFrame();
        EXPECT_TRUE(allFinite(cuda->image()));
    }
}

TEST_F(CudaVsCpu, OverflowingPhotonMapGrowsAndTheFirstFrameIsRedone) {
    // Albedo 0.9 in a closed sphere stores ~9 photons per path; room for 1 per path overflows.
    Scene scene;
    std::uint32_t m = scene.addMaterial("wall", makeDiffuse(glm::vec3(0.9f)));
    scene.addSphere(glm::vec3(0.0f), 1.0f, m);
    scene.addPointLight(glm::vec3(0.0f), glm::vec3(10.0f));
    scene.camera.position = glm::vec3(0.0f);
    scene.camera.lookAt = glm::vec3(0, 0, -1);
    scene.finalize();
    RenderSettings s;
    s.width = 32;
    s.height = 32;
    s.photons = 20000;
    s.maxPhotonDepth = 64;
    s.photonCapacity = 1.0f;
    s.radius = 0.2f;
    auto cuda = createBackend("cuda", BackendOptions{"", false, true});
    auto cpu = createBackend("cpu");
    test::StageOutputs actual = test::renderStages(*cuda, scene, s);
    test::StageOutputs expected = test::renderStages(*cpu, scene, s);
    EXPECT_LE(actual.stats.stored[MAP_GLOBAL], actual.stats.capacity[MAP_GLOBAL]);
    test::expectSamePhotonMaps(actual.maps, expected.maps);
}

}  // namespace
}  // namespace photon
