// Stochastic progressive photon mapping and the automatic radii, on the CPU backend against the
// converged references of tests/data/ (tests/data/README.md has the commands that made them):
// the error falls with frames and below the progressive estimate's, a caustic's peak converges to
// the reference's, an object far outside the view changes nothing, and a seed repeats exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/frame/scene_settings.h"
#include "core/render/devices.h"
#include "backend_compare.h"
#include "core/image/image_error.h"
#include "core/loaders/scene_loader.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "test_render.h"
#include "test_util.h"

namespace photon {
namespace {

// The scene at the reference's size, pixel centres (as the references were made).
RenderSettings referenceSettings(const Scene& scene, Estimator estimator, std::uint32_t photons) {
    RenderSettings s = test::sizedSettings(scene.render, 64, 48, photons);
    s.pixelCenter = true;
    s.estimator = estimator;
    s.seed = 3;
    return s;
}

// The backend's image after each of `checkpoints` frame counts.
std::vector<Image> renderCheckpoints(const Scene& scene, const RenderSettings& settings, std::vector<std::uint32_t> checkpoints) {
    auto backend = createRenderer("cpu");
    backend->setScene(scene);
    backend->setSettings(settings);
    std::vector<Image> images;
    std::uint32_t frames = 0;
    for (std::uint32_t target : checkpoints) {
        while (frames < target) {
            backend->renderFrame();
            frames += 1;
        }
        images.push_back(backend->image());
    }
    return images;
}

TEST(Sppm, ErrorFallsWithFramesAndStaysBelowProgressive) {
    Scene scene = loadSceneFile(test::scenesDir() + "/smallpt.json");
    Image reference = readImage(test::dataPath("smallpt-64x48.pfm"));
    std::vector<std::uint32_t> checkpoints = {4, 16, 64};
    std::vector<double> sppm;
    for (const Image& image : renderCheckpoints(scene, referenceSettings(scene, Estimator::Sppm, 40000), checkpoints)) {
        sppm.push_back(relativeRmse(image, reference));
    }
    std::vector<double> progressive;
    for (const Image& image : renderCheckpoints(scene, referenceSettings(scene, Estimator::Progressive, 40000), checkpoints)) {
        progressive.push_back(relativeRmse(image, reference));
    }
    for (std::size_t i = 0; i < checkpoints.size(); ++i) {
        std::printf("smallpt 64x48, %u frames of 40k photons: sppm %.4f, progressive %.4f\n", checkpoints[i], sppm[i],
                    progressive[i]);
    }
    EXPECT_LT(sppm[1], sppm[0]);
    EXPECT_LT(sppm[2], 0.75 * sppm[0]);
    EXPECT_LT(sppm[2], progressive[2]);
    // First radii from the photon density (measured 0.148, 0.112, 0.076); from the footprints
    // alone they were 0.198, 0.174, 0.148.
    EXPECT_LT(sppm[2], 0.1);
}

TEST(Sppm, CausticPeakConvergesToTheReference) {
    Scene scene = loadSceneFile(test::scenesDir() + "/caustic.json");
    Image reference = readImage(test::dataPath("caustic-64x48.pfm"));
    Window window = brightestWindow(reference, 2);
    // The first radii come from the photon density, so a dense focus starts sharp; then the radii
    // shrink with the photons traced (R² ~ N^-(1-α)). Against the reference (1G photons) 16 frames
    // of 25k photons measured a peak of 0.919 and an energy of 1.028, 2048 frames 1.050 and 1.025
    // (from footprint radii they were 0.740 and 1.076 after 16 frames, 0.876 and 1.015 after 2048).
    RenderSettings settings = referenceSettings(scene, Estimator::Sppm, 25000);
    std::vector<std::uint32_t> checkpoints = {16, 2048};
    std::vector<Image> images = renderCheckpoints(scene, settings, checkpoints);
    std::vector<ImageError> errors;
    for (std::size_t i = 0; i < images.size(); ++i) {
        errors.push_back(compareWithReference(images[i], reference, window));
        std::printf("caustic 64x48, %u frames: peak %.3f, energy %.3f of the reference's, rmse %.4f\n", checkpoints[i],
                    errors[i].peakRatio, errors[i].energyRatio, errors[i].whole);
    }
    EXPECT_NEAR(errors.front().peakRatio, 1.0, 0.15) << "the first radii resolve the focus";
    EXPECT_NEAR(errors.back().peakRatio, 1.0, 0.1);
    EXPECT_GT(errors.back().peakRatio, errors.front().peakRatio + 0.08) << "the focus sharpens as the radii shrink";
    EXPECT_NEAR(errors.back().energyRatio, 1.0, 0.03);
    EXPECT_LT(errors.back().whole, 0.5 * errors.front().whole);
}

// An object far outside the view must not change the automatic radii nor the grid: the global
// map's light is the same with it.
TEST(Sppm, FarObjectKeepsTheIndirectLight) {
    for (Estimator estimator : {Estimator::Radius, Estimator::Sppm}) {
        Scene near = defaultScene();
        Scene far = defaultScene();
        std::uint32_t grey = far.addMaterial("grey", makeDiffuse(glm::vec3(0.5f)));
        far.addSphere(glm::vec3(1e9f, 0.0f, 0.0f), 0.1f, grey);
        far.addSphere(glm::vec3(0.0f, -1e9f, 0.0f), 0.1f, grey);
        far.finalize();
        RenderSettings s = test::sizedSettings(near.render, 64, 48, 50000);
        s.estimator = estimator;
        s.view = View::Global;
        double mean[2];
        int i = 0;
        for (const Scene* scene : {&near, &far}) {
            std::vector<Image> images = renderCheckpoints(*scene, s, {4});
            mean[i++] = meanLuminance(images.back());
        }
        SCOPED_TRACE(toString(estimator));
        EXPECT_GT(mean[0], 0.0);
        EXPECT_NEAR(mean[1] / mean[0], 1.0, 0.02) << "indirect light with and without the far spheres";
    }
}

TEST(Sppm, SameSeedRepeatsAndACameraChangeRestarts) {
    Scene scene = defaultScene();
    RenderSettings s = test::sizedSettings(scene.render, 48, 36, 20000);
    s.estimator = Estimator::Sppm;
    Image first = renderCheckpoints(scene, s, {3}).back();
    Image second = renderCheckpoints(scene, s, {3}).back();
    EXPECT_EQ(test::differingPixels(first, second), 0u);
    // Three frames, a camera "change" that restarts, three frames: the statistics start again.
    auto backend = createRenderer("cpu");
    test::renderFrames(*backend, scene, s, 3);
    backend->setCamera(scene.camera);
    for (int f = 0; f < 3; ++f) {
        backend->renderFrame();
    }
    Image restarted = backend->image();
    EXPECT_TRUE(allFinite(restarted));
    EXPECT_LT(relativeRmse(restarted, first), 0.5);
    EXPECT_GT(test::differingPixels(restarted, first), 0u) << "frames 4-6 have their own random numbers";
}

// Automatic radii come from the image: the same scene at twice the resolution gets half the radius.
TEST(AutomaticRadius, FollowsThePixelFootprint) {
    Scene scene = defaultScene();
    RenderSettings s = scene.render;
    float radius[2];
    for (int i = 0; i < 2; ++i) {
        s.width = i == 0 ? 160 : 320;
        s.height = i == 0 ? 120 : 240;
        FrameRadii r = firstFrameRadii(scene, s, measureFootprints(scene, scene.camera, s), planPhotons(scene, s));
        radius[i] = r.radius[MAP_GLOBAL];
        EXPECT_NEAR(r.radius[MAP_CAUSTIC], 0.5f * r.radius[MAP_GLOBAL], 1e-6f);
    }
    EXPECT_NEAR(radius[1] / radius[0], 0.5, 0.05);
    s.radius = 0.07f;
    EXPECT_FLOAT_EQ(firstFrameRadii(scene, s, measureFootprints(scene, scene.camera, s), planPhotons(scene, s)).radius[MAP_GLOBAL], 0.07f)
        << "a given radius overrides";
}

// On a bounded grid an automatic radius stays within the cells its query reaches, for every
// estimator and map (issue 57: sppm's small, low-photon renders were refused, blaming the
// automatic radius); a given one too large is refused by its flag.
TEST(AutomaticRadius, StaysWithinTheBoundedGrid) {
    for (const char* file : {"cornell.json", "fog.json"}) {
        Scene scene = loadSceneFile(std::string(PHOTON_SCENES_DIR) + "/" + file);
        for (Estimator e : {Estimator::Sppm, Estimator::Radius, Estimator::Progressive, Estimator::Knn}) {
            RenderSettings s = test::sizedSettings(scene.render, 64, 48, 5000);
            s.estimator = e;
            s.grid = GridKind::Bounded;
            glm::vec3 extent = scene.boundsMax - scene.boundsMin;
            float cell = std::max({extent.x, extent.y, extent.z}) / float(s.gridResolution);
            FrameRadii r = firstFrameRadii(scene, s, measureFootprints(scene, scene.camera, s), planPhotons(scene, s));
            for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
                EXPECT_LE(r.radius[m], boundedGridReachCells(m) * cell * 1.000001f) << file << " map " << m;
                EXPECT_GT(r.radius[m], 0.0f);
            }
            EXPECT_NO_THROW(validateForScene(s, scene, r)) << file;
            EXPECT_TRUE(allFinite(test::renderOnCpu(scene, s, 2))) << file;
        }
    }
    Scene scene = defaultScene();
    RenderSettings s = test::sizedSettings(scene.render, 64, 48, 5000);
    s.grid = GridKind::Bounded;
    s.radius = 1.0f;
    auto backend = createRenderer("cpu");
    try {
        test::renderFrames(*backend, scene, s, 1);
        ADD_FAILURE() << "a given radius of 1 on 64 cells of a 2-unit box";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("--radius 1: too large for the bounded grid"), std::string::npos) << e.what();
    }
}

// The cells of the next frame follow the largest radius too, not only the median, whose histogram
// ends at 2^32: with --radius 1e12 every pixel's query walked 233³ cells of 2^32 (a 64×48 render
// took 100 s; 1e15 never ended).
TEST(SppmCells, FollowTheLargestRadius) {
    for (float radius : {1e12f, 1e15f}) {
        Scene scene = defaultScene();
        RenderSettings s = test::sizedSettings(scene.render, 64, 48, 20000);
        s.estimator = Estimator::Sppm;
        s.radius = radius;
        auto backend = createRenderer("cpu");
        test::renderFrames(*backend, scene, s, 1);
        // The second frame's grids, as it would run (not run: the old cells made it hang).
        const FrameParams& next = backend->beginFrame();
        // A frame shrinks a pixel's radius by √α at most (R'² = R²(N + αM)/(N + M)).
        EXPECT_GE(next.grids[MAP_GLOBAL].cellSize, 0.999f * radius * std::sqrt(s.alpha) / kSppmCellReach) << radius;
        EXPECT_TRUE(std::isfinite(next.grids[MAP_GLOBAL].cellSize));
    }
    std::uint32_t histogram[SPPM_RADIUS_BINS] = {};
    histogram[SPPM_RADIUS_BINS / 2] = 10;  // radii in [1, 2)
    EXPECT_FLOAT_EQ(sppmCellRadius(histogram, 1.5f), 2.0f) << "the median's bin, when it holds the largest";
    EXPECT_FLOAT_EQ(sppmCellRadius(histogram, 64.0f), 64.0f / kSppmCellReach);
    EXPECT_FLOAT_EQ(sppmCellRadius(histogram, std::numeric_limits<float>::infinity()), 2.0f);
    std::uint32_t none[SPPM_RADIUS_BINS] = {};
    EXPECT_EQ(sppmCellRadius(none, 64.0f), 0.0f) << "no pixel has photons";
}

TEST(SppmSettings, FinalGatherIsRefused) {
    RenderSettings s;
    s.estimator = Estimator::Sppm;
    s.globalMode = GlobalMode::FinalGather;
    EXPECT_THROW(validateSettings(s), InputError);
}

}  // namespace
}  // namespace photon
