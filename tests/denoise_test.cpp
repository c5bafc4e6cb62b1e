// The denoiser (shared/denoise.h) and the auxiliary images it is guided by (shared/aov.h), on the
// CPU backend: it keeps energy (the furnace, a flat wall), lowers the error against the converged
// references of tests/data/ without raising it at edges (where the reference changes fast) or in
// a caustic's focus, keeps textures, and the AOVs are what they say. (Vulkan against the CPU:
// tests/vulkan_backend_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "core/render/devices.h"
#include "shared/denoise.h"
#include "core/frame/aov_images.h"
#include "core/image/image_error.h"
#include "core/loaders/scene_loader.h"
#include "test_render.h"
#include "test_util.h"

namespace photon {
namespace {

struct Renders {
    Image raw;
    Image denoised;
    std::vector<PixelAov> aovs;
};

// `frames` frames of the scene on the CPU with the denoiser on: the image without and with it.
Renders render(const Scene& scene, RenderSettings settings, std::uint32_t frames) {
    settings.denoise = Denoise::On;
    auto backend = createRenderer("cpu");
    test::renderFrames(*backend, scene, settings, frames);
    Renders r;
    r.denoised = backend->image();
    r.raw = backend->rawImage();
    r.aovs = backend->readAovs();
    return r;
}

// The raw and the denoised image of `frames` frames at the photons and size of `settings` (sppm,
// seed 3), measured against the reference.
std::pair<Quality, Quality> rawAndDenoised(const char* sceneFile, const char* referenceFile, RenderSettings settings,
                                           std::uint32_t frames) {
    Scene scene = loadSceneFile(test::scenesDir() + "/" + sceneFile);
    Image reference = readImage(test::dataPath(referenceFile));
    RenderSettings s = test::sizedSettings(scene.render, settings.width, settings.height, settings.photons);
    s.estimator = Estimator::Sppm;
    s.seed = 3;
    Renders r = render(scene, s, frames);
    QualityMasks masks(reference);
    return {measureQuality(r.raw, reference, masks), measureQuality(r.denoised, reference, masks)};
}

double meanLuminanceIn(const Image& image, std::uint32_t x0, std::uint32_t y0, std::uint32_t x1, std::uint32_t y1) {
    double sum = 0.0;
    for (std::uint32_t y = y0; y < y1; ++y) {
        for (std::uint32_t x = x0; x < x1; ++x) {
            sum += luminance(image.at(x, y));
        }
    }
    return sum / double((x1 - x0) * (y1 - y0));
}

// Radiance 1 everywhere inside the sphere: the filter must neither gain nor lose any of it.
TEST(Denoise, KeepsTheFurnaceEnergyAndLowersItsNoise) {
    Scene scene = loadSceneFile(test::scenesDir() + "/furnace.json");
    RenderSettings s = test::sizedSettings(scene.render, 64, 48, 20000);
    s.estimator = Estimator::Sppm;
    Renders r = render(scene, s, 4);
    double raw = meanLuminance(r.raw);
    double denoised = meanLuminance(r.denoised);
    auto deviation = [](const Image& image) {
        double sum = 0.0;
        for (const glm::vec4& p : image.pixels) {
            sum += (luminance(p) - 1.0) * (luminance(p) - 1.0);
        }
        return std::sqrt(sum / double(image.pixels.size()));
    };
    std::printf("furnace: mean %.4f raw, %.4f denoised; rms deviation from 1: %.4f raw, %.4f denoised\n", raw,
                denoised, deviation(r.raw), deviation(r.denoised));
    EXPECT_NEAR(denoised / raw, 1.0, 0.01);
    EXPECT_LT(deviation(r.denoised), 0.5 * deviation(r.raw));
}

// The Cornell box's back wall, a flat diffuse surface: its mean stays within 1%.
TEST(Denoise, KeepsAFlatWallsEnergy) {
    Scene scene = loadSceneFile(test::scenesDir() + "/cornell.json");
    RenderSettings s = test::sizedSettings(scene.render, 160, 120, 20000);
    s.estimator = Estimator::Sppm;
    Renders r = render(scene, s, 4);
    // The back wall between the side walls, above the balls (cornell.json's camera).
    double raw = meanLuminanceIn(r.raw, 50, 25, 110, 60);
    double denoised = meanLuminanceIn(r.denoised, 50, 25, 110, 60);
    std::printf("back wall: mean %.4f raw, %.4f denoised\n", raw, denoised);
    EXPECT_NEAR(denoised / raw, 1.0, 0.01);
}

// Against the converged Cornell box (tests/data/README.md), at 320 × 240 and 8 frames of the
// README's photon density (a photon a frame per 3 pixels): lower error away from the focus
// (outside the reference's brightest 0.5%) and better SSIM, no more error at the reference's edges
// (silhouettes, shadow boundaries), and the focus keeps its energy within 2%. (Smaller images are
// ruled by the estimate's blur, not its noise: there a filter has nothing to remove.)
TEST(Denoise, LowersTheErrorAndKeepsEdgesAndTheCaustic) {
    auto [raw, denoised] = rawAndDenoised("cornell.json", "cornell-320x240.pfm", test::sizedSettings({}, 320, 240, 25000), 8);
    std::printf("cornell: away from the focus %.4f raw, %.4f denoised; SSIM %.4f, %.4f; edges %.4f, %.4f; "
                "focus energy %.4f, %.4f\n", raw.away, denoised.away, raw.ssim, denoised.ssim, raw.edges,
                denoised.edges, raw.focusEnergy, denoised.focusEnergy);
    EXPECT_LT(denoised.away, 0.97 * raw.away);
    EXPECT_GT(denoised.ssim, raw.ssim + 0.01);
    EXPECT_LE(denoised.edges, raw.edges * 1.02);
    EXPECT_NEAR(denoised.focusEnergy / raw.focusEnergy, 1.0, 0.02);
}

// textured.glb's checker, bricks and metal squares survive: demodulation and the albedo weight
// filter the light, not the textures. A blurred texture would raise the error at the reference's
// edges, here mostly the textures' own.
TEST(Denoise, KeepsTextures) {
    auto [raw, denoised] = rawAndDenoised("textured.glb", "textured-128x96.pfm", test::sizedSettings({}, 128, 96, 4000), 8);
    std::printf("textured.glb: rmse %.4f raw, %.4f denoised; edges %.4f, %.4f; SSIM %.4f, %.4f\n", raw.whole,
                denoised.whole, raw.edges, denoised.edges, raw.ssim, denoised.ssim);
    EXPECT_LE(denoised.whole, raw.whole * 1.01);
    EXPECT_LE(denoised.edges, raw.edges * 1.01);
    EXPECT_GE(denoised.ssim, raw.ssim - 0.002);
}

// The AOVs of a scene whose every pixel sees a diffuse wall head on: albedo, normal and depth are
// the wall's, coverage 1; the variance image is finite and not negative.
// The levels' guides, packed into 16 bytes: the normal to 16-bit octahedral precision, the albedo
// to 10 bits (clamped to its range), depth and slope as they are, no surface as a zero normal.
TEST(Denoise, GuidesSurvivePacking) {
    DenoiseGuide g;
    g.normal = normalize(vec3(0.3f, -0.8f, -0.52f));
    g.albedo = vec3(0.0f, 0.731f, 5.0f);
    g.depth = 12.345f;
    g.slope = 0.0172f;
    DenoiseGuide back = unpackDenoiseGuide(packDenoiseGuide(g));
    EXPECT_NEAR(dot(unitVector(back.normal), g.normal), 1.0f, 1.0e-7f);
    EXPECT_EQ(back.albedo.x, 0.0f);
    EXPECT_NEAR(back.albedo.y, 0.731f, DENOISE_ALBEDO_RANGE / 2046.0f);
    EXPECT_EQ(back.albedo.z, DENOISE_ALBEDO_RANGE);
    EXPECT_EQ(back.depth, g.depth);
    EXPECT_EQ(back.slope, g.slope);
    // The normal weight of a surface against itself stays 1 after packing, and is cos^128.
    EXPECT_NEAR(normalWeight(g.normal, back.normal), 1.0f, 1.0e-4f);
    vec3 tilted = normalize(g.normal + vec3(0.1f, 0.0f, 0.0f));
    EXPECT_NEAR(normalWeight(tilted, back.normal), std::pow(dot(tilted, g.normal), 128.0f), 1.0e-3f);
    EXPECT_EQ(normalWeight(-g.normal, back.normal), 0.0f);

    g.normal = vec3(0.0f);
    back = unpackDenoiseGuide(packDenoiseGuide(g));
    EXPECT_EQ(back.normal, vec3(0.0f));
    EXPECT_EQ(back.depth, g.depth);
}

TEST(Aov, AreTheSurfaceTheCameraSees) {
    Scene s;
    std::uint32_t grey = s.addMaterial("grey", makeDiffuse(glm::vec3(0.25f, 0.5f, 0.75f)));
    s.addPlane(glm::vec3(0, 0, -3), glm::vec3(0, 0, 1), grey);
    s.addPointLight(glm::vec3(0, 0, 0), glm::vec3(10.0f));
    s.camera.position = glm::vec3(0.0f);
    s.camera.lookAt = glm::vec3(0, 0, -1);
    s.camera.fovY = 30.0f;
    s.finalize();
    RenderSettings settings = test::sizedSettings({}, 16, 12, 2000);
    settings.aov = true;
    auto backend = createRenderer("cpu");
    test::renderFrames(*backend, s, settings, 3);
    std::vector<PixelAov> aovs = backend->readAovs();
    ASSERT_EQ(aovs.size(), 16u * 12u);
    AovImages images = aovImages(aovs, 16, 12, 3);
    for (std::size_t i = 0; i < aovs.size(); ++i) {
        EXPECT_NEAR(aovs[i].albedo.x, 0.25f, 1e-5f);
        EXPECT_NEAR(aovs[i].albedo.z, 0.75f, 1e-5f);
        EXPECT_NEAR(aovs[i].normal.z, 1.0f, 1e-5f);
        EXPECT_GE(aovs[i].depth, 3.0f - 1e-4f);  // the distance to the wall: 3 at the centre, more beside it
        EXPECT_LE(aovs[i].depth, 3.3f);
        EXPECT_EQ(aovs[i].coverage, 1.0f);
        EXPECT_GE(images.variance.pixels[i].x, 0.0f);
        EXPECT_TRUE(std::isfinite(images.variance.pixels[i].x));
    }
    settings.aov = false;
    backend->setSettings(settings);
    backend->renderFrame();
    EXPECT_TRUE(backend->readAovs().empty());
}

}  // namespace
}  // namespace photon
