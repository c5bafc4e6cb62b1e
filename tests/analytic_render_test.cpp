// Renders with known answers, on the CPU backend:
//   furnace:   a point light of power Φ at the centre of a closed diffuse sphere (radius R,
//              albedo ρ): the radiance everywhere is ρΦ / (4π²R²(1−ρ)).
//   ball lens: a glass sphere (index n, radius R) under a narrow parallel beam focuses at
//              nR / (2(n−1)) from its centre (paraxial); the caustic's peak along the axis is there.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "apps/backends.h"
#include "core/loaders/scene_loader.h"
#include "test_util.h"

namespace photon {
namespace {

constexpr double kPi = 3.14159265358979323846;

Scene furnaceScene(float radius, float albedo, float power) {
    Scene s;
    s.name = "furnace";
    std::uint32_t m = s.addMaterial("wall", makeDiffuse(glm::vec3(albedo)));
    s.addSphere(glm::vec3(0.0f), radius, m);
    s.addPointLight(glm::vec3(0.0f), glm::vec3(power));
    s.camera.position = glm::vec3(0.0f);
    s.camera.lookAt = glm::vec3(0.3f, 0.2f, -1.0f);
    s.camera.fovY = 90.0f;
    s.finalize();
    return s;
}

TEST(Furnace, RadianceEverywhereIsRhoPhiOver4Pi2R2OneMinusRho) {
    for (Estimator estimator : {Estimator::Radius, Estimator::Knn, Estimator::Progressive, Estimator::Sppm}) {
        const float R = 2.0f;
        const float rho = 0.5f;
        const float phi = 10.0f;
        Scene scene = furnaceScene(R, rho, phi);
        RenderSettings settings;
        settings.width = 48;
        settings.height = 48;
        settings.photons = 200000;
        settings.frames = 4;
        settings.estimator = estimator;
        settings.radius = 0.15f;
        settings.k = 64;
        settings.maxPhotonDepth = 64;
        auto backend = createBackend("cpu");
        backend->setScene(scene);
        backend->setSettings(settings);
        for (std::uint32_t f = 0; f < settings.frames; ++f) {
            backend->renderFrame();
        }
        Image image = backend->image();
        double expected = rho * phi / (4.0 * kPi * kPi * R * R * (1.0 - rho));
        double mean = 0.0;
        double squares = 0.0;
        for (const glm::vec4& p : image.pixels) {
            mean += p.x;
            squares += (p.x - expected) * (p.x - expected);
        }
        mean /= double(image.pixels.size());
        double rms = std::sqrt(squares / double(image.pixels.size())) / expected;
        std::printf("furnace %s: mean/expected %.4f, pixel rms %.4f\n", toString(estimator), mean / expected, rms);
        EXPECT_NEAR(mean / expected, 1.0, 0.01) << toString(estimator);
        EXPECT_LT(rms, 0.05) << toString(estimator) << ": pixels scatter too much";
    }
}

// A glass ball of radius 1 at the origin; a spot light 1000 away sends rays within 0.1R of the
// z axis (nearly parallel); a diffuse screen perpendicular to the axis at z = screen.
Scene ballLensScene(float ior, float screen) {
    Scene s;
    std::uint32_t glass = s.addMaterial("glass", makeGlass(ior, glm::vec3(1.0f)));
    std::uint32_t white = s.addMaterial("white", makeDiffuse(glm::vec3(0.8f)));
    s.addSphere(glm::vec3(0.0f), 1.0f, glass);
    s.addQuad(glm::vec3(-2.0f, -2.0f, screen), glm::vec3(4, 0, 0), glm::vec3(0, 4, 0), white);
    float distance = 1000.0f;
    float angle = float(std::atan(0.1 / distance) * 180.0 / kPi);
    s.addSpotLight(glm::vec3(0.0f, 0.0f, -distance), glm::vec3(0, 0, 1), glm::vec3(1.0f), angle, angle);
    s.camera.position = glm::vec3(3.0f, 0.0f, 0.0f);
    s.camera.lookAt = glm::vec3(0.0f);
    s.finalize();
    return s;
}

TEST(BallLens, CausticPeaksAtTheParaxialFocus) {
    const float n = 1.5f;
    const double focus = n * 1.0 / (2.0 * (n - 1.0));
    const float probe = 0.001f;  // radius of the on-axis density probe
    double bestZ = 0.0;
    double bestDensity = -1.0;
    for (int i = 0; i <= 40; ++i) {
        float z = 1.40f + 0.005f * float(i);
        RenderSettings settings;
        settings.width = 4;
        settings.height = 4;
        settings.photons = 200000;
        settings.causticFraction = 0.99f;
        settings.causticRadius = probe;
        auto backend = createBackend("cpu");
        backend->setScene(ballLensScene(n, z));
        backend->setSettings(settings);
        backend->renderFrame();
        PhotonMaps maps = backend->readPhotonMaps();
        double density = 0.0;
        for (const Photon& p : maps.photons[MAP_CAUSTIC]) {
            if (p.position.x * p.position.x + p.position.y * p.position.y < probe * probe) {
                density += p.power.x;
            }
        }
        if (density > bestDensity) {
            bestDensity = density;
            bestZ = z;
        }
    }
    std::printf("ball lens: caustic peak at z = %.3f, paraxial focus %.3f\n", bestZ, focus);
    EXPECT_GT(bestDensity, 0.0);
    EXPECT_NEAR(bestZ / focus, 1.0, 0.02) << "peak at z = " << bestZ << ", paraxial focus " << focus;
}

Image renderCornell(std::uint32_t frames, std::uint32_t seed) {
    Scene scene = defaultScene();
    RenderSettings settings = scene.render;
    settings.width = 64;
    settings.height = 48;
    settings.photons = 20000;
    settings.estimator = Estimator::Progressive;
    settings.radius = 0.08f;
    settings.causticRadius = 0.05f;
    settings.seed = seed;
    auto backend = createBackend("cpu");
    backend->setScene(scene);
    backend->setSettings(settings);
    for (std::uint32_t f = 0; f < frames; ++f) {
        backend->renderFrame();
    }
    return backend->image();
}

TEST(Progressive, ErrorFallsAsFramesGrow) {
    Image reference = renderCornell(512, 99);
    double previous = INFINITY;
    for (std::uint32_t frames : {2u, 8u, 32u, 128u}) {
        double error = relativeRmse(renderCornell(frames, 1), reference);
        std::printf("progressive: %u frames, relative RMSE %.4f\n", frames, error);
        EXPECT_LT(error, previous) << frames << " frames";
        previous = error;
    }
    EXPECT_LT(previous, 0.1);
}

TEST(Progressive, SameSeedSameImage) {
    Image a = renderCornell(3, 7);
    Image b = renderCornell(3, 7);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_EQ(0, std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec4)));
    Image c = renderCornell(3, 8);
    EXPECT_NE(0, std::memcmp(a.pixels.data(), c.pixels.data(), a.pixels.size() * sizeof(glm::vec4)));
}

}  // namespace
}  // namespace photon
