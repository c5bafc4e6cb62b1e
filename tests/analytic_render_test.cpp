// Renders with known answers made of analytic spheres, on the CPU backend (known_answers.h has
// the answers): the furnace and the ball lens; and the progressive estimate's convergence.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/render/devices.h"
#include "core/loaders/scene_loader.h"
#include "known_answers.h"
#include "test_util.h"

namespace photon {
namespace {

TEST(Furnace, RadianceEverywhereIsRhoPhiOver4Pi2R2OneMinusRho) {
    for (Estimator estimator : {Estimator::Radius, Estimator::Knn, Estimator::Progressive, Estimator::Sppm}) {
        const float R = 2.0f;
        const float rho = 0.5f;
        const float phi = 10.0f;
        Scene scene = test::furnaceScene(rho, phi, [&](Scene& s, std::uint32_t wall) { s.addSphere(glm::vec3(0.0f), R, wall); });
        RenderSettings settings = test::furnaceSettings(estimator);
        settings.k = 64;
        Image image = test::renderOnCpu(scene, settings, settings.frames);
        double expected = test::furnaceRadiance(R, rho, phi);
        double mean = test::meanRed(image);
        double squares = 0.0;
        for (const glm::vec4& p : image.pixels) {
            squares += (p.x - expected) * (p.x - expected);
        }
        double rms = std::sqrt(squares / double(image.pixels.size())) / expected;
        std::printf("furnace %s: mean/expected %.4f, pixel rms %.4f\n", toString(estimator), mean / expected, rms);
        EXPECT_NEAR(mean / expected, 1.0, 0.01) << toString(estimator);
        EXPECT_LT(rms, 0.05) << toString(estimator) << ": pixels scatter too much";
    }
}

TEST(BallLens, CausticPeaksAtTheParaxialFocus) {
    const float n = 1.5f;
    const double focus = test::paraxialFocus(n);
    const float probe = 0.001f;  // radius of the on-axis density probe
    Scene lens = test::ballLensScene(n, [](Scene& s, std::uint32_t glass) { s.addSphere(glm::vec3(0.0f), 1.0f, glass); });
    test::CausticPeak peak = test::findCausticPeak(lens, probe);
    std::printf("ball lens: caustic peak at z = %.3f, paraxial focus %.3f\n", peak.z, focus);
    test::expectPeakAtFocus(peak, focus);
}

Image renderCornell(std::uint32_t frames, std::uint32_t seed) {
    Scene scene = defaultScene();
    RenderSettings settings = test::sizedSettings(scene.render, 64, 48, 20000);
    settings.estimator = Estimator::Progressive;
    settings.radius = 0.08f;
    settings.causticRadius = 0.05f;
    settings.seed = seed;
    return test::renderOnCpu(scene, settings, frames);
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
