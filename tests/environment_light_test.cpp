// The environment light against answers known in closed form, on every backend this machine has:
//   furnace:    a convex Lambertian sphere of albedo ρ under a uniform environment L has radiance
//               ρL everywhere; its photons bring the irradiance πL to every point of it;
//   one texel:  a map black but for one small texel lights the scene as a directional light of the
//               same irradiance from that direction does, shadows and the caustic of a glass ball
//               included;
//   importance: the map's sampling finds a small bright region with far fewer samples than
//               uniform sampling of the sphere at equal error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/render/devices.h"
#include "core/system/error.h"
#include "shared/environment.h"
#include "shared/rng.h"
#include "known_answers.h"
#include "test_util.h"

namespace photon {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Every backend that runs here: the CPU, and Vulkan (with its validation layer) and CUDA where a
// device exists.
std::vector<std::unique_ptr<Renderer>> backendsHere() {
    std::vector<std::unique_ptr<Renderer>> backends;
    for (const std::string& name : compiledBackends()) {
        DeviceOptions options;
        options.validation = name == "vulkan";
        try {
            backends.push_back(createRenderer(name, options));
        } catch (const RuntimeError& e) {
            std::printf("%s: not here (%s)\n", name.c_str(), e.what());
        }
    }
    return backends;
}

// A map of width × height texels, black but for texel (x, y) of radiance `value`.
EnvironmentMap oneTexelMap(std::uint32_t width, std::uint32_t height, std::uint32_t x, std::uint32_t y, float value) {
    EnvironmentMap map;
    map.width = width;
    map.height = height;
    map.texels.assign(std::size_t(width) * height, glm::vec3(0.0f));
    map.texels[std::size_t(y) * width + x] = glm::vec3(value);
    return map;
}

// The solid angle of a texel of row y of a map `height` rows high and `width` columns wide.
double texelSolidAngle(std::uint32_t width, std::uint32_t height, std::uint32_t y) {
    double theta0 = kPi * y / height;
    double theta1 = kPi * (y + 1) / height;
    return 2.0 * kPi / width * (std::cos(theta0) - std::cos(theta1));
}

// A grey sphere of radius 1 filling the view, under `env`.
Scene furnaceUnder(EnvironmentLight env, float albedo) {
    Scene s;
    s.addSphere(glm::vec3(0.0f), 1.0f, s.addMaterial("grey", makeDiffuse(glm::vec3(albedo))));
    s.setEnvironment(std::move(env));
    s.camera.position = glm::vec3(0.0f, 0.0f, 1.6f);
    s.camera.lookAt = glm::vec3(0.0f);
    s.camera.fovY = 30.0f;  // the sphere covers the whole image
    s.finalize();
    return s;
}

EnvironmentLight uniformEnvironment(glm::vec3 radiance) {
    EnvironmentLight env;
    env.radiance = radiance;
    env.lights = true;
    return env;
}

// The same uniform radiance as a map, turned: what the map's sampling, its pdf and MIS give.
EnvironmentLight uniformMap(float radiance) {
    EnvironmentLight env;
    env.map.width = 32;
    env.map.height = 16;
    env.map.texels.assign(32 * 16, glm::vec3(radiance));
    env.radiance = glm::vec3(1.0f);
    env.rotation = environmentRotation(30.0f, glm::vec3(1.0f, 0.5f, 0.0f));
    env.lights = true;
    return env;
}

TEST(EnvironmentFurnace, ConvexSphereHasRadianceRhoLWithShadowRays) {
    const float rho = 0.5f;
    for (auto& backend : backendsHere()) {
        for (bool asMap : {false, true}) {
            Scene scene = furnaceUnder(asMap ? uniformMap(2.0f) : uniformEnvironment(glm::vec3(2.0f)), rho);
            RenderSettings settings = test::sizedSettings({}, 32, 32, 20000);
            test::renderFrames(*backend, scene, settings, 8);
            double mean = test::meanRed(backend->image());
            std::printf("%s, %s: mean / ρL = %.4f\n", backend->name().c_str(), asMap ? "map" : "uniform", mean / (rho * 2.0));
            EXPECT_NEAR(mean / (rho * 2.0), 1.0, 0.01) << backend->name() << (asMap ? " map" : " uniform");
        }
    }
}

// Photons only: every photon's first surface is the sphere (later bounces leave it, convex), so
// the global map of a final-gather frame holds the flux that arrives, πL · 4πa²; and a density
// estimate anywhere on it gives the irradiance πL, radiance ρL.
TEST(EnvironmentFurnace, PhotonsBringTheIrradiancePiLEverywhere) {
    const float rho = 0.5f;
    const float L = 2.0f;
    for (auto& backend : backendsHere()) {
        for (bool asMap : {false, true}) {
            Scene scene = furnaceUnder(asMap ? uniformMap(L) : uniformEnvironment(glm::vec3(L)), rho);
            RenderSettings settings = test::sizedSettings({}, 8, 8, 400000);
            settings.estimator = Estimator::Radius;
            settings.globalMode = GlobalMode::FinalGather;
            settings.maxPhotonDepth = 1;  // the first surface only
            backend->setScene(scene);
            backend->setSettings(settings);
            double flux = 0.0;
            double nearPole = 0.0;
            constexpr int kFrames = 4;
            const double r = 0.2;
            for (int f = 0; f < kFrames; ++f) {
                backend->renderFrame();
                for (const Photon& p : backend->readPhotonMaps().photons[MAP_GLOBAL]) {
                    flux += p.power.x;
                    if (glm::length(p.position - glm::vec3(0.0f, 0.0f, 1.0f)) < r) {
                        nearPole += p.power.x;
                    }
                }
            }
            flux /= kFrames;
            // The cap of chord radius r about a pole has area πr² exactly on a unit sphere.
            double irradiance = nearPole / kFrames / (kPi * r * r);
            double expected = kPi * L * 4.0 * kPi;
            std::printf("%s, %s: flux / 4π²L = %.4f, ρE/π / ρL = %.4f\n", backend->name().c_str(), asMap ? "map" : "uniform",
                        flux / expected, rho * irradiance / kPi / (rho * L));
            EXPECT_NEAR(flux / expected, 1.0, 0.01) << backend->name();
            EXPECT_NEAR(irradiance / (kPi * L), 1.0, 0.03) << backend->name() << ": the estimate at a pole";
        }
    }
}

// A floor with a diffuse ball and a glass ball, lit by `light`.
Scene ballsOnAFloor(const std::function<void(Scene&)>& light) {
    Scene s;
    s.addQuad(glm::vec3(-2, 0, 2), glm::vec3(4, 0, 0), glm::vec3(0, 0, -4), s.addMaterial("floor", makeDiffuse(glm::vec3(0.7f))));
    s.addSphere(glm::vec3(-0.7f, 0.5f, 0.0f), 0.5f, s.addMaterial("grey", makeDiffuse(glm::vec3(0.5f))));
    s.addSphere(glm::vec3(0.7f, 0.5f, 0.0f), 0.5f, s.addMaterial("glass", makeGlass(1.5f, glm::vec3(1.0f))));
    light(s);
    s.camera.position = glm::vec3(0.0f, 3.0f, 3.0f);
    s.camera.lookAt = glm::vec3(0.0f, 0.3f, 0.0f);
    s.camera.fovY = 50.0f;
    s.finalize();
    return s;
}

// Whole image and caustic of one small texel against the directional light it equals.
TEST(EnvironmentImportance, OneBrightTexelEqualsADirectionalLight) {
    const std::uint32_t w = 1024, h = 512, x = 600, y = 120;  // a texel 37° from the zenith
    const float value = 5.0e4f;
    EnvironmentMap map = oneTexelMap(w, h, x, y, value);
    glm::vec3 toward = equirectDirection((x + 0.5f) / w, (y + 0.5f) / h);
    double irradiance = value * texelSolidAngle(w, h, y);
    Scene lit = ballsOnAFloor([&](Scene& s) {
        EnvironmentLight env;
        env.map = map;
        env.radiance = glm::vec3(1.0f);
        env.lights = true;
        s.setEnvironment(std::move(env));
    });
    Scene sun = ballsOnAFloor([&](Scene& s) { s.addDirectionalLight(-toward, glm::vec3(float(irradiance))); });
    for (auto& backend : backendsHere()) {
        if (backend->name() == "vulkan") {
            continue;  // lavapipe's share is the bit-exact comparison of vulkan_backend_test.cpp
        }
        RenderSettings settings = test::sizedSettings({}, 64, 48, 100000);
        settings.causticFraction = 0.5f;
        auto render = [&](const Scene& scene, View view) {
            RenderSettings s = settings;
            s.view = view;
            test::renderFrames(*backend, scene, s, 24);
            return backend->image();
        };
        double whole = test::meanRed(render(lit, View::Final)) / test::meanRed(render(sun, View::Final));
        Image litCaustic = render(lit, View::Caustic);
        Image sunCaustic = render(sun, View::Caustic);
        double energy = test::meanRed(litCaustic) / test::meanRed(sunCaustic);
        float peakLit = 0.0f;
        float peakSun = 0.0f;
        for (std::size_t i = 0; i < litCaustic.pixels.size(); ++i) {
            peakLit = std::max(peakLit, litCaustic.pixels[i].x);
            peakSun = std::max(peakSun, sunCaustic.pixels[i].x);
        }
        std::printf("%s: environment / directional: image %.4f, caustic energy %.4f, caustic peak %.4f\n",
                    backend->name().c_str(), whole, energy, peakLit / peakSun);
        EXPECT_NEAR(whole, 1.0, 0.01) << backend->name();
        EXPECT_NEAR(energy, 1.0, 0.02) << backend->name();
        EXPECT_NEAR(peakLit / peakSun, 1.0, 0.02) << backend->name();
    }
}

// Irradiance on an upward surface from a map of a dim sky with a small bright patch: the samples
// uniform sphere sampling needs for the error of the map's sampling with N samples, over N.
TEST(EnvironmentImportance, SmallBrightRegionNeedsTenTimesFewerSamples) {
    EnvironmentMap map;
    map.width = 256;
    map.height = 128;
    map.texels.assign(256 * 128, glm::vec3(0.05f));
    for (std::uint32_t y = 30; y < 34; ++y) {
        for (std::uint32_t x = 100; x < 104; ++x) {
            map.texels[y * 256 + x] = glm::vec3(400.0f);
        }
    }
    Scene scene;
    scene.addSphere(glm::vec3(0.0f), 1.0f, scene.addMaterial("grey", makeDiffuse(glm::vec3(0.5f))));
    EnvironmentLight env;
    env.map = map;
    env.radiance = glm::vec3(1.0f);
    env.lights = true;
    scene.setEnvironment(std::move(env));
    test::SceneBindings sb(scene);
    const Light& light = sb.scene.lights[sb.scene.environmentLight];
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    // Variance of one sample of E = ∫ L cos dω, each way, over many samples.
    auto variance = [&](bool importance) {
        Rng rng = rngCreate(7u, 0u, 0u, STREAM_PHOTON);
        double sum = 0.0, squares = 0.0;
        const int n = 400000;
        for (int i = 0; i < n; ++i) {
            float u1 = rngNext(rng);
            float u2 = rngNext(rng);
            glm::vec3 d;
            float pdf;
            glm::vec3 radiance;
            if (importance) {
                radiance = sampleEnvironment(sb.bindings, light, u1, u2, d, pdf);
            } else {
                d = sampleUniformSphere(u1, u2);
                pdf = INV_FOUR_PI;
                radiance = environmentRadiance(sb.bindings, light, d);
            }
            double e = pdf > 0.0f ? radiance.x * std::max(0.0f, glm::dot(d, up)) / pdf : 0.0;
            sum += e;
            squares += e * e;
        }
        double mean = sum / n;
        return std::pair{mean, squares / n - mean * mean};
    };
    auto [meanImportance, varImportance] = variance(true);
    auto [meanUniform, varUniform] = variance(false);
    std::printf("irradiance: importance %.4f, uniform %.4f; samples for equal error: %.1f× fewer\n", meanImportance,
                meanUniform, varUniform / varImportance);
    EXPECT_NEAR(meanImportance / meanUniform, 1.0, 0.02);
    EXPECT_GE(varUniform / varImportance, 10.0);
}

// Radiance's shared exponent keeps every channel within 1/256 of the largest, over the float range.
TEST(EnvironmentMaps, RgbeKeepsColoursWithinItsPrecision) {
    for (float scale : {1e-30f, 1e-6f, 0.01f, 1.0f, 1.9999f, 2.0f, 3.0e4f, 1.0e9f, 1.0e30f, 3.0e38f}) {
        glm::vec3 c = glm::vec3(1.0f, 0.5f, 0.01f) * scale;
        glm::vec3 d = decodeRgbe(encodeRgbe(c));
        float largest = std::min(c.x, 1.7e38f);  // RGBE's largest value is 255.5 · 2^119
        EXPECT_NEAR(d.x, largest, largest / 200.0f) << scale;
        EXPECT_NEAR(d.y, std::min(c.y, largest), largest / 200.0f) << scale;
        EXPECT_NEAR(d.z, c.z, largest / 200.0f) << scale;
    }
    EXPECT_EQ(encodeRgbe(glm::vec3(0.0f)), 0u);
    EXPECT_EQ(decodeRgbe(0u), glm::vec3(0.0f));
}

// Maps that give nothing to sample: black everywhere, one texel, one texel that is black.
TEST(EnvironmentMaps, DegenerateMapsRenderFiniteImages) {
    std::vector<EnvironmentMap> maps = {oneTexelMap(16, 8, 3, 2, 0.0f), oneTexelMap(1, 1, 0, 0, 3.0f),
                                        oneTexelMap(1, 1, 0, 0, 0.0f), oneTexelMap(2, 1, 1, 0, 1.0f)};
    for (auto& backend : backendsHere()) {
        for (const EnvironmentMap& map : maps) {
            Scene scene = ballsOnAFloor([&](Scene& s) {
                s.addPointLight(glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(10.0f));
                EnvironmentLight env;
                env.map = map;
                env.radiance = glm::vec3(1.0f);
                env.lights = true;
                s.setEnvironment(std::move(env));
            });
            RenderSettings settings = test::sizedSettings({}, 16, 12, 5000);
            test::renderFrames(*backend, scene, settings, 2);
            EXPECT_TRUE(allFinite(backend->image())) << backend->name() << " " << map.width << "x" << map.height;
        }
    }
}

}  // namespace
}  // namespace photon
