// glTF's metallic-roughness BSDF (shared/pbr.h), checked as Mitsuba and pbrt-v4 check theirs:
//   white furnace: with a white base colour the reflected energy E(ωo) = ∫ f cos dωi is at most 1,
//                  and the mean sample weight (what paths carry) equals a quadrature of evalBsdf
//                  within 1% over a grid of metallic × roughness × view angles;
//   χ²:           the sampled directions follow pdfPbr;
//   transmission: a smooth white glass reflects and transmits everything (E = 1);
//   coverage:     an alpha-masked surface is absent for rays where its texture's alpha is below
//                 the cutoff, a blended one present in proportion to alpha, a single-sided one
//                 absent from behind;
//   volume:       photons through an absorbing slab arrive with exp(−σd) of their power.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/render/devices.h"
#include "core/scene/scene.h"
#include "shared/bsdf.h"
#include "shared/intersect.h"
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

// A unit square of two triangles at z = 0 facing +z, texture s across x, with a 2×1 texture
// whose left texel is transparent (α 0) and right one opaque.
Scene coverageScene(std::uint32_t flags, float alpha) {
    Scene s;
    std::vector<glm::uvec2> texels = {glm::uvec2(0xffffffffu, 0x0000ffffu), glm::uvec2(0xffffffffu, 0xffffffffu)};
    std::uint32_t texture = s.addTexture(2, 1, texels, WRAP_CLAMP, WRAP_CLAMP);
    Material m = makePbr(vec3(0.8f), 0.0f, 1.0f);
    m.albedoTexture = texture;
    m.flags = flags;
    m.alpha = alpha;
    std::uint32_t material = s.addMaterial("leaf", m);
    Mesh mesh;
    mesh.positions = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(1, 1, 0), vec3(0, 1, 0)};
    mesh.texcoords = {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)};
    mesh.triangles = {glm::uvec3(0, 1, 2), glm::uvec3(0, 2, 3)};
    mesh.materials = {material, material};
    s.addMesh(mesh, glm::mat4(1.0f));
    s.addPointLight(vec3(0.5f, 0.5f, 5.0f), vec3(1.0f));
    return s;
}

TEST(Coverage, AlphaMaskCutsOutWhereTheTextureIsTransparent) {
    test::SceneBindings sb(coverageScene(MATERIAL_FLAG_ALPHA_MASK, 1.0f));
    Hit hit;
    auto down = [](float x) { return makeRay(vec3(x, 0.5f, 1.0f), vec3(0, 0, -1), FLOAT_MAX); };
    EXPECT_FALSE(traceClosest(sb.bindings, down(0.1f), hit)) << "α 0 under the cutoff: a hole";
    EXPECT_TRUE(traceClosest(sb.bindings, down(0.9f), hit)) << "α 1: solid";
    EXPECT_FALSE(traceOccluded(sb.bindings, vec3(0.1f, 0.5f, 1.0f), vec3(0, 0, -1), 2.0f)) << "shadow rays too";
    EXPECT_TRUE(traceOccluded(sb.bindings, vec3(0.9f, 0.5f, 1.0f), vec3(0, 0, -1), 2.0f));
    // The same square opaque: every ray hits.
    test::SceneBindings opaque(coverageScene(0u, 1.0f));
    EXPECT_TRUE(traceClosest(opaque.bindings, down(0.1f), hit));
}

TEST(Coverage, SingleSidedSurfacesHaveNoBack) {
    test::SceneBindings sb(coverageScene(MATERIAL_FLAG_SINGLE_SIDED, 1.0f));
    Hit hit;
    EXPECT_TRUE(traceClosest(sb.bindings, makeRay(vec3(0.9f, 0.5f, 1.0f), vec3(0, 0, -1), FLOAT_MAX), hit)) << "its front";
    EXPECT_FALSE(traceClosest(sb.bindings, makeRay(vec3(0.9f, 0.5f, -1.0f), vec3(0, 0, 1), FLOAT_MAX), hit)) << "its back";
    Scene glass = coverageScene(MATERIAL_FLAG_SINGLE_SIDED, 1.0f);
    glass.materials[0].transmission = 1.0f;
    test::SceneBindings through(glass);
    EXPECT_TRUE(traceClosest(through.bindings, makeRay(vec3(0.9f, 0.5f, -1.0f), vec3(0, 0, 1), FLOAT_MAX), hit))
        << "a transmissive surface keeps its back";
}

TEST(Coverage, AlphaBlendIsPresentInProportionToAlpha) {
    test::SceneBindings sb(coverageScene(MATERIAL_FLAG_ALPHA_BLEND, 0.3f));
    int hits = 0;
    constexpr int kRays = 20000;
    Rng rng = rngCreate(5u, 0u, 0u, 0u);
    for (int i = 0; i < kRays; ++i) {
        // Rays that land beyond the opaque texel's centre (α = 0.3 · 1) and inside the square.
        float x = 0.76f + 0.1f * rngNext(rng);
        float y = 0.05f + 0.8f * rngNext(rng);
        vec3 d = glm::normalize(vec3(0.1f * rngNext(rng), 0.1f * rngNext(rng), -1.0f));
        Hit hit;
        hits += traceClosest(sb.bindings, makeRay(vec3(x, y, 1.0f), d, FLOAT_MAX), hit) ? 1 : 0;
    }
    EXPECT_NEAR(double(hits) / kRays, 0.3, 0.02);
}

// A directional light through a glass slab of thickness d onto a floor: with the same random
// numbers every photon path is the same, so the caustic map's power under an absorbing slab is
// exp(−σd) of a clear one's, channel by channel.
TEST(Volume, PhotonsThroughAnAbsorbingSlabLoseExpMinusSigmaD) {
    const float d = 0.5f;
    const vec3 sigma(0.2f, 1.0f, 3.0f);
    auto causticPower = [&](vec3 attenuation) {
        Scene s;
        Material glass = makePbr(vec3(1.0f), 0.0f, 0.0f);
        glass.transmission = 1.0f;
        glass.attenuation = attenuation;
        std::uint32_t slab = s.addMaterial("slab", glass);
        std::uint32_t floor = s.addMaterial("floor", makeDiffuse(vec3(0.5f)));
        Mesh box;
        for (int i = 0; i < 8; ++i) {
            box.positions.push_back(vec3(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f + d : 1.0f));
        }
        box.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                         {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
        box.materials.assign(box.triangles.size(), slab);
        s.addMesh(box, glm::mat4(1.0f));
        s.addQuad(vec3(-0.5f, -0.5f, 0.0f), vec3(1, 0, 0), vec3(0, 1, 0), floor);
        s.addDirectionalLight(vec3(0, 0, -1), vec3(1.0f));
        s.camera.position = vec3(0, -3, 3);
        s.camera.lookAt = vec3(0);
        s.finalize();
        RenderSettings settings;
        settings.width = 4;
        settings.height = 4;
        settings.photons = 50000;
        auto backend = createRenderer("cpu");
        backend->setScene(std::move(s));
        backend->setSettings(settings);
        backend->renderFrame();
        glm::dvec3 sum(0.0);
        for (const Photon& p : backend->readPhotonMaps().photons[MAP_CAUSTIC]) {
            sum += glm::dvec3(p.power);
        }
        return sum;
    };
    glm::dvec3 clear = causticPower(vec3(0.0f));
    glm::dvec3 absorbed = causticPower(sigma);
    ASSERT_GT(clear.x, 0.0);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(absorbed[c] / clear[c], std::exp(-double(sigma[c]) * d), 2e-3) << "channel " << c;
    }
}

}  // namespace
}  // namespace photon
