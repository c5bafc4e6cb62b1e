// The photon pass: the aimed caustic pass and the plain global pass divide caustic paths between
// them without losing or double-counting any, and the maps hold the flux they should.
#include <gtest/gtest.h>

#include "core/render/devices.h"
#include "core/loaders/scene_loader.h"
#include "test_render.h"
#include "test_util.h"

namespace photon {
namespace {

// Total flux in each map after one frame, averaged over a few frames.
glm::dvec2 mapFlux(const Scene& scene, float causticFraction, std::uint32_t seed) {
    RenderSettings settings = test::sizedSettings({}, 4, 4, 400000);
    settings.causticFraction = causticFraction;
    settings.seed = seed;
    auto backend = createRenderer("cpu");
    backend->setScene(scene);
    backend->setSettings(settings);
    glm::dvec2 flux(0.0);
    constexpr int kFrames = 3;
    for (int f = 0; f < kFrames; ++f) {
        backend->renderFrame();
        PhotonMaps maps = backend->readPhotonMaps();
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            for (const Photon& p : maps.photons[m]) {
                flux[int(m)] += p.power.x + p.power.y + p.power.z;
            }
        }
    }
    return flux / double(kFrames);
}

// A glass ball and a mirror ball (caustic targets), a mirror plane and a mirror-coated floor
// (not targets), a diffuse box around them.
Scene causticMix() {
    Scene s;
    std::uint32_t white = s.addMaterial("white", makeDiffuse(glm::vec3(0.7f)));
    std::uint32_t glass = s.addMaterial("glass", makeGlass(1.5f, glm::vec3(1.0f)));
    std::uint32_t mirror = s.addMaterial("mirror", makeMirror(glm::vec3(0.9f)));
    std::uint32_t floor = s.addMaterial("coated", makeReflective(glm::vec3(0.4f), glm::vec3(0.4f)));
    s.addQuad(glm::vec3(-2, 0, -2), glm::vec3(0, 0, 4), glm::vec3(4, 0, 0), floor);
    s.addQuad(glm::vec3(-2, 3, -2), glm::vec3(4, 0, 0), glm::vec3(0, 0, 4), white);
    s.addQuad(glm::vec3(-2, 0, -2), glm::vec3(4, 0, 0), glm::vec3(0, 3, 0), white);
    s.addQuad(glm::vec3(-2, 0, 2), glm::vec3(0, 3, 0), glm::vec3(4, 0, 0), white);
    s.addQuad(glm::vec3(-2, 0, -2), glm::vec3(0, 3, 0), glm::vec3(0, 0, 4), white);
    s.addPlane(glm::vec3(1.99f, 0, 0), glm::vec3(-1, 0, 0), mirror);
    s.addSphere(glm::vec3(-0.6f, 0.5f, 0.3f), 0.5f, glass);
    s.addSphere(glm::vec3(0.7f, 0.4f, -0.5f), 0.4f, mirror);
    s.addHemisphereLight(glm::vec3(0, 2.9f, 0), glm::vec3(0, -1, 0), glm::vec3(10.0f));
    s.finalize();
    return s;
}

TEST(PhotonPass, CausticPassAndGlobalPassAgreeOnCausticFlux) {
    Scene scene = causticMix();
    glm::dvec2 plain = mapFlux(scene, 0.0f, 1);
    glm::dvec2 split = mapFlux(scene, 0.5f, 2);
    ASSERT_GT(plain.y, 0.0);
    EXPECT_NEAR(split.y / plain.y, 1.0, 0.02) << "caustic map flux, split " << split.y << " plain " << plain.y;
    EXPECT_NEAR(split.x / plain.x, 1.0, 0.02) << "global map flux, split " << split.x << " plain " << plain.x;
}

}  // namespace
}  // namespace photon

namespace photon {
namespace {

// Subsampling dense cells (gather budget) must not change the expected estimate: the caustic of
// the Cornell box averaged over frames with a harsh budget equals the exhaustive gather.
TEST(GatherBudget, SubsamplingDenseCellsIsUnbiased) {
    auto render = [](std::uint32_t budget) {
        Scene scene = defaultScene();
        RenderSettings s = test::sizedSettings(scene.render, 96, 72, 60000);
        s.view = View::Caustic;
        s.gatherBudget = budget;
        return test::renderOnCpu(scene, s, 48);
    };
    Image exhaustive = render(0);
    Image subsampled = render(8);
    double a = meanLuminance(subsampled);
    double b = meanLuminance(exhaustive);
    EXPECT_NEAR(a / b, 1.0, 0.01);
    EXPECT_LT(relativeRmse(subsampled, exhaustive), 0.05);
}

}  // namespace
}  // namespace photon
