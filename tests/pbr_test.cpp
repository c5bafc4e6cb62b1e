// glTF's metallic-roughness BSDF (shared/pbr.h), checked as Mitsuba and pbrt-v4 check theirs:
//   white furnace: with a white base colour the reflected energy E(ωo) = ∫ f cos dωi is at most 1,
//                  and the mean sample weight (what paths carry) equals a quadrature of evalBsdf
//                  within 1% over a grid of metallic × roughness × view angles;
//   χ²:           the sampled directions follow pdfPbr;
//   transmission: a smooth white glass reflects and transmits everything (E = 1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/scene.h"
#include "shared/bsdf.h"
#include "test_util.h"

namespace photon {
namespace {

constexpr double kPi = 3.14159265358979323846;

vec3 viewAt(float cosO) { return vec3(std::sqrt(1.0f - cosO * cosO), 0.0f, cosO); }

// ∫ f(ωo, ωi) cosθi dωi over the hemisphere by the midpoint rule in (cosθ, φ), with cells
// refined towards the mirror direction where narrow lobes live.
double reflectedEnergy(const Material& m, vec3 wo) {
    vec3 n(0, 0, 1);
    constexpr int kTheta = 1200;
    constexpr int kPhi = 1600;
    double sum = 0.0;
    for (int i = 0; i < kTheta; ++i) {
        // cosθ = 1 − x², x uniform: cells shrink towards the pole of grazing-free directions
        double x0 = double(i) / kTheta;
        double x1 = double(i + 1) / kTheta;
        double xm = 0.5 * (x0 + x1);
        double cosT = 1.0 - xm * xm;
        double dCos = (1.0 - x0 * x0) - (1.0 - x1 * x1);
        double sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
        for (int j = 0; j < kPhi; ++j) {
            double phi = (j + 0.5) * 2.0 * kPi / kPhi;
            vec3 wi(float(sinT * std::cos(phi)), float(sinT * std::sin(phi)), float(cosT));
            sum += double(evalBsdf(m, wo, wi, n).x) * cosT * dCos * (2.0 * kPi / kPhi);
        }
    }
    return sum;
}

double meanWeight(const Material& m, vec3 wo, int samples, double* transmitted = nullptr) {
    vec3 n(0, 0, 1);
    Rng rng = rngCreate(7u, 1u, 2u, 3u);
    double sum = 0.0;
    double through = 0.0;
    for (int i = 0; i < samples; ++i) {
        BsdfSample bs = sampleBsdf(m, wo, n, n, rng);
        sum += bs.weight.x;
        if (bs.direction.z < 0.0f) {
            through += bs.weight.x;
        }
    }
    if (transmitted) {
        *transmitted = through / samples;
    }
    return sum / samples;
}

TEST(PbrBsdf, WhiteFurnaceConservesEnergyAndSamplingMatchesEval) {
    for (float metallic : {0.0f, 0.5f, 1.0f}) {
        for (float roughness : {0.35f, 0.5f, 0.75f, 1.0f}) {
            Material m = makePbr(vec3(1.0f), metallic, roughness);
            for (float cosO : {0.9f, 0.5f, 0.2f}) {
                vec3 wo = viewAt(cosO);
                double reference = reflectedEnergy(m, wo);
                double sampled = meanWeight(m, wo, 400000);
                EXPECT_LE(reference, 1.0 + 1e-3) << "metallic " << metallic << " roughness " << roughness;
                EXPECT_NEAR(sampled, reference, 0.01 * reference)
                    << "metallic " << metallic << " roughness " << roughness << " cosθo " << cosO;
            }
        }
    }
}

TEST(PbrBsdf, ColouredBaseReflectsLessThanWhite) {
    Material white = makePbr(vec3(1.0f), 0.3f, 0.6f);
    Material red = makePbr(vec3(0.8f, 0.2f, 0.1f), 0.3f, 0.6f);
    vec3 wo = viewAt(0.7f);
    vec3 n(0, 0, 1);
    Rng rng = rngCreate(1u, 2u, 3u, 4u);
    vec3 sum(0.0f);
    for (int i = 0; i < 100000; ++i) {
        sum += sampleBsdf(red, wo, n, n, rng).weight;
    }
    sum /= 100000.0f;
    double whiteEnergy = reflectedEnergy(white, wo);
    EXPECT_LT(sum.x, whiteEnergy);
    EXPECT_GT(sum.x, sum.y);
    EXPECT_GT(sum.y, sum.z);
    EXPECT_GT(sum.z, 0.04f * 0.5f) << "the dielectric coat reflects white whatever the base colour";
}

// Smooth lobes sampled without their delta-like evaluation: the sampler alone conserves energy.
TEST(PbrBsdf, SmoothMetalAndGlassReflectOrTransmitEverything) {
    Material metal = makePbr(vec3(1.0f), 1.0f, 0.0f);
    EXPECT_NEAR(meanWeight(metal, viewAt(0.6f), 20000), 1.0, 1e-4);
    Material glass = makePbr(vec3(1.0f), 0.0f, 0.0f);
    glass.transmission = 1.0f;
    for (bool thin : {false, true}) {
        glass.flags = thin ? MATERIAL_FLAG_THIN_WALLED : 0u;
        double transmitted = 0.0;
        double total = meanWeight(glass, viewAt(0.8f), 100000, &transmitted);
        EXPECT_NEAR(total, 1.0, 1e-4) << (thin ? "thin" : "volume");
        EXPECT_GT(transmitted, 0.9) << "at near-normal incidence most light passes";
    }
    // A rough glass loses only what Smith's single scattering loses, and never gains.
    glass.flags = 0u;
    glass.roughness = 0.25f;
    double rough = meanWeight(glass, viewAt(0.8f), 100000);
    EXPECT_LE(rough, 1.0 + 1e-3);
    EXPECT_GT(rough, 0.9);
}

// χ² of sampled directions against pdfPbr over a (cosθ, φ) grid.
TEST(PbrBsdf, SamplingFollowsItsPdf) {
    constexpr int kTheta = 16;
    constexpr int kPhi = 32;
    constexpr int kSamples = 400000;
    vec3 n(0, 0, 1);
    for (float metallic : {0.0f, 0.6f}) {
        for (float roughness : {0.4f, 0.8f}) {
            Material m = makePbr(vec3(0.7f, 0.5f, 0.3f), metallic, roughness);
            vec3 wo = viewAt(0.6f);
            std::vector<double> observed(kTheta * kPhi, 0.0);
            Rng rng = rngCreate(11u, 0u, 0u, 0u);
            int absorbed = 0;
            for (int i = 0; i < kSamples; ++i) {
                BsdfSample bs = sampleBsdf(m, wo, n, n, rng);
                if (bs.lobe == LOBE_NONE) {
                    absorbed += 1;
                    continue;
                }
                double cosT = std::clamp(double(bs.direction.z), 0.0, 1.0);
                double phi = std::atan2(double(bs.direction.y), double(bs.direction.x));
                if (phi < 0.0) {
                    phi += 2.0 * kPi;
                }
                int a = std::min(kTheta - 1, int((1.0 - cosT) * kTheta));
                int b = std::min(kPhi - 1, int(phi / (2.0 * kPi) * kPhi));
                observed[std::size_t(a * kPhi + b)] += 1.0;
            }
            // Expected counts: the pdf integrated over each cell (8×8 midpoints), times the samples
            // that were not absorbed (directions below the surface are absorbed, their pdf is not 0).
            std::vector<double> expected(kTheta * kPhi, 0.0);
            double mass = 0.0;
            for (int a = 0; a < kTheta; ++a) {
                for (int b = 0; b < kPhi; ++b) {
                    double cell = 0.0;
                    for (int p = 0; p < 8; ++p) {
                        for (int q = 0; q < 8; ++q) {
                            double cosT = 1.0 - (a + (p + 0.5) / 8.0) / kTheta;
                            double phi = (b + (q + 0.5) / 8.0) / kPhi * 2.0 * kPi;
                            double sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
                            vec3 wi(float(sinT * std::cos(phi)), float(sinT * std::sin(phi)), float(cosT));
                            cell += pdfPbr(m, wo, wi, n, PBR_LOBES_ALL);
                        }
                    }
                    expected[std::size_t(a * kPhi + b)] = cell / 64.0 * (1.0 / kTheta) * (2.0 * kPi / kPhi);
                    mass += expected[std::size_t(a * kPhi + b)];
                }
            }
            ASSERT_GT(mass, 0.5);
            ASSERT_LE(mass, 1.0 + 1e-2);
            for (double& e : expected) {
                e *= double(kSamples - absorbed) / mass;
            }
            int dof = 0;
            double chi2 = test::chiSquare(observed, expected, dof);
            EXPECT_LT(chi2, test::chiSquareThreshold(dof)) << "metallic " << metallic << " roughness " << roughness;
        }
    }
}

}  // namespace
}  // namespace photon
