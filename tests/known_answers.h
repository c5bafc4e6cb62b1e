// The renders with known answers, which analytic_render_test.cpp makes of spheres and
// mesh_render_test.cpp of triangles, on the CPU backend:
//   furnace:   a point light of power Φ at the centre of a closed diffuse sphere (radius R,
//              albedo ρ): the radiance everywhere is ρΦ / (4π²R²(1−ρ)).
//   ball lens: a glass sphere (index n, radius 1) under a narrow parallel beam focuses at
//              n / (2(n−1)) from its centre (paraxial); the caustic's peak along the axis is there.
// Each test adds its own sphere (`addSphere`, `addBall`); the rest of the scene, the settings and
// the measurement are the same for both.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>

#include "test_render.h"

namespace photon::test {

constexpr double kPi = 3.14159265358979323846;

// The furnace: a diffuse material of `albedo` for `addSphere` to make the enclosure of (centred
// on the origin), a point light of `power` at the centre, and the camera there too.
inline Scene furnaceScene(float albedo, float power, const std::function<void(Scene&, std::uint32_t wall)>& addSphere) {
    Scene s;
    s.name = "furnace";
    std::uint32_t wall = s.addMaterial("wall", makeDiffuse(glm::vec3(albedo)));
    addSphere(s, wall);
    s.addPointLight(glm::vec3(0.0f), glm::vec3(power));
    s.camera.position = glm::vec3(0.0f);
    s.camera.lookAt = glm::vec3(0.3f, 0.2f, -1.0f);
    s.camera.fovY = 90.0f;
    s.finalize();
    return s;
}

// ρΦ / (4π²R²(1−ρ)): the radiance everywhere inside the furnace.
inline double furnaceRadiance(float radius, float albedo, float power) {
    return albedo * power / (4.0 * kPi * kPi * radius * radius * (1.0 - albedo));
}

// Four frames of 48 × 48 with many photons and paths long enough for the enclosure's bounces.
inline RenderSettings furnaceSettings(Estimator estimator) {
    RenderSettings s = sizedSettings({}, 48, 48, 200000);
    s.frames = 4;
    s.estimator = estimator;
    s.radius = 0.15f;
    s.maxPhotonDepth = 64;
    return s;
}

// The mean of the pixels' red values (the furnace is grey).
inline double meanRed(const Image& image) {
    double mean = 0.0;
    for (const glm::vec4& p : image.pixels) {
        mean += p.x;
    }
    return mean / double(image.pixels.size());
}

// n R / (2(n−1)) for R = 1: where a ball of index n focuses a parallel beam, from its centre.
inline double paraxialFocus(float n) { return n / (2.0 * (n - 1.0)); }

// The ball lens without its screen: a glass of index `ior` for `addBall` to make a ball of radius
// 1 at the origin of, a spot light 1000 away whose rays pass within 0.1 of the z axis (nearly
// parallel), and a camera looking at the ball from the side.
inline Scene ballLensScene(float ior, const std::function<void(Scene&, std::uint32_t glass)>& addBall) {
    Scene s;
    std::uint32_t glass = s.addMaterial("glass", makeGlass(ior, glm::vec3(1.0f)));
    addBall(s, glass);
    float distance = 1000.0f;
    float angle = float(std::atan(0.1 / distance) * 180.0 / kPi);
    s.addSpotLight(glm::vec3(0.0f, 0.0f, -distance), glm::vec3(0, 0, 1), glm::vec3(1.0f), angle, angle);
    s.camera.position = glm::vec3(3.0f, 0.0f, 0.0f);
    s.camera.lookAt = glm::vec3(0.0f);
    return s;
}

struct CausticPeak {
    double z = 0.0;         // the screen's place where the density peaked
    double density = -1.0;  // the power of the caustic photons within the probe there
};

// Moves a diffuse screen perpendicular to the axis through z = first … first + 0.2 (steps of
// 0.005) behind the lens; at each place, one frame of nearly only caustic paths (with `base`'s
// other settings), and the power of the caustic photons within `probe` of the axis.
inline CausticPeak findCausticPeak(const Scene& lens, float probe, const RenderSettings& base = {}, float first = 1.40f) {
    CausticPeak peak;
    for (int i = 0; i <= 40; ++i) {
        float z = first + 0.005f * float(i);
        Scene s = lens;
        std::uint32_t white = s.addMaterial("white", makeDiffuse(glm::vec3(0.8f)));
        s.addQuad(glm::vec3(-2.0f, -2.0f, z), glm::vec3(4, 0, 0), glm::vec3(0, 4, 0), white);
        s.finalize();
        RenderSettings settings = sizedSettings(base, 4, 4, 200000);
        settings.causticFraction = 0.99f;
        settings.causticRadius = probe;
        auto backend = createRenderer("cpu");
        backend->setScene(std::move(s));
        backend->setSettings(settings);
        backend->renderFrame();
        PhotonMaps maps = backend->readPhotonMaps();
        double density = 0.0;
        for (const Photon& p : maps.photons[MAP_CAUSTIC]) {
            if (p.position.x * p.position.x + p.position.y * p.position.y < probe * probe) {
                density += p.power.x + p.power.y + p.power.z;
            }
        }
        if (density > peak.density) {
            peak.density = density;
            peak.z = z;
        }
    }
    return peak;
}

// The caustic was found, and it peaks within 2% of the paraxial focus.
inline void expectPeakAtFocus(const CausticPeak& peak, double focus) {
    EXPECT_GT(peak.density, 0.0);
    EXPECT_NEAR(peak.z / focus, 1.0, 0.02) << "peak at z = " << peak.z << ", paraxial focus " << focus;
}

}  // namespace photon::test
