// Light emission is unbiased: the mean photon power equals the flux the light sends where the
// photons are aimed, for the global pass and for the caustic pass (cones towards specular
// objects, clipped to spot cones). Checked against brute force with the global pass.
#include <gtest/gtest.h>

#include "shared/eye_trace.h"
#include "shared/lights.h"
#include "shared/photon_trace.h"
#include "test_util.h"

namespace photon {
namespace {

constexpr int kN = 400000;

Scene sceneWithTargets(std::vector<std::pair<vec3, float>> glassSpheres) {
    Scene s;
    std::uint32_t glass = s.addMaterial("glass", makeGlass(1.5f, vec3(1.0f)));
    for (auto [c, r] : glassSpheres) {
        s.addSphere(c, r, glass);
    }
    return s;
}

// Mean power of caustic-pass photons from light 0.
vec3 meanCausticPower(const test::SceneBindings& sb) {
    Rng rng = rngCreate(0u, 0u, 5u, STREAM_PHOTON);
    dvec3 sum(0.0);
    for (int i = 0; i < kN; ++i) {
        PhotonEmission e = emitCausticPhoton(sb.bindings, sb.scene.lights[0], rng);
        sum += dvec3(e.power);
    }
    return vec3(sum / double(kN));
}

// Flux of light 0 (global-pass emission) carried by rays that hit any sphere, by brute force:
// 4M rays, so that even a 1% hit rate has 0.5% noise.
vec3 fluxHittingSpheres(const test::SceneBindings& sb) {
    constexpr int kRays = 10 * kN;
    Rng rng = rngCreate(0u, 0u, 6u, STREAM_PHOTON);
    dvec3 sum(0.0);
    for (int i = 0; i < kRays; ++i) {
        PhotonEmission e = emitPhoton(sb.bindings, sb.scene.lights[0], rng);
        Ray r = makeRay(e.origin, e.direction, FLOAT_MAX);
        for (const Sphere& s : sb.scene.spheres) {
            if (intersectSphere(r, s.center, s.radius, FLOAT_MAX) < FLOAT_MAX) {
                sum += dvec3(e.power);
                break;
            }
        }
    }
    return vec3(sum / double(kRays));
}

TEST(Emission, GlobalPassCarriesTheLightsFlux) {
    Scene s;
    s.addSpotLight(vec3(0), vec3(0, -1, 0), vec3(10.0f), 30.0f, 20.0f);
    s.addHemisphereLight(vec3(0), vec3(0, 1, 0), vec3(10.0f));
    s.addQuadLight(vec3(0), vec3(1, 0, 0), vec3(0, 0, 1), vec3(10.0f));
    test::SceneBindings sb(s);
    for (const Light& light : sb.scene.lights) {
        Rng rng = rngCreate(0u, 0u, 1u, STREAM_PHOTON);
        double sum = 0.0;
        for (int i = 0; i < kN; ++i) {
            sum += emitPhoton(sb.bindings, light, rng).power.x;
        }
        EXPECT_NEAR(sum / kN, 10.0, 0.05) << "light type " << light.type;
    }
}

TEST(Emission, CausticPassFromPointLightMatchesSolidAngle) {
    Scene s = sceneWithTargets({{vec3(3, 0, 0), 1.0f}});
    s.addPointLight(vec3(0), vec3(8.0f));
    test::SceneBindings sb(s);
    // Isotropic: flux into the cone = Φ · 2π(1 - cosθ) / 4π.
    double x = 1.0 - std::sqrt(1.0 - 1.0 / 9.0);
    EXPECT_NEAR(meanCausticPower(sb).x, 8.0 * x / 2.0, 1e-3);
}

TEST(Emission, CausticPassFromOverlappingTargetsIsUnbiased) {
    Scene s = sceneWithTargets({{vec3(3, 0, 0), 1.0f}, {vec3(3, 0.8f, 0.3f), 0.7f}, {vec3(-2, 1, 0), 0.5f}});
    s.addHemisphereLight(vec3(0), vec3(1, 0.2f, 0), vec3(5.0f));
    test::SceneBindings sb(s);
    vec3 aimed = meanCausticPower(sb);
    vec3 brute = fluxHittingSpheres(sb);
    EXPECT_NEAR(aimed.x, brute.x, 0.02 * brute.x);
}

TEST(Emission, CausticPassUsesASpotConeInsideTheTarget) {
    // A narrow spot aimed at a large sphere: every photon goes into the spot's cone, none is
    // wasted, and together they carry the spot's whole flux.
    Scene s = sceneWithTargets({{vec3(0, -5, 0), 2.0f}});
    s.addSpotLight(vec3(0), vec3(0, -1, 0), vec3(3.0f), 5.0f, 2.0f);
    test::SceneBindings sb(s);
    Rng rng = rngCreate(0u, 0u, 5u, STREAM_PHOTON);
    int zero = 0;
    double sum = 0.0;
    for (int i = 0; i < kN; ++i) {
        PhotonEmission e = emitCausticPhoton(sb.bindings, sb.scene.lights[0], rng);
        zero += isBlack(e.power) ? 1 : 0;
        sum += e.power.x;
    }
    EXPECT_LT(zero, kN / 1000);
    EXPECT_NEAR(sum / kN, 3.0, 0.01);
}

TEST(Emission, CausticPassSkipsTargetsOutsideTheSpot) {
    Scene s = sceneWithTargets({{vec3(0, 5, 0), 1.0f}});
    s.addSpotLight(vec3(0), vec3(0, -1, 0), vec3(3.0f), 20.0f, 20.0f);
    test::SceneBindings sb(s);
    EXPECT_EQ(meanCausticPower(sb).x, 0.0f);
}

TEST(Emission, CausticPassFromAreaLightsIsUnbiased) {
    Scene s = sceneWithTargets({{vec3(0.3f, -2, 0.2f), 0.6f}, {vec3(-1, -1.5f, 0.5f), 0.3f}});
    s.addQuadLight(vec3(-0.5f, 0, -0.5f), vec3(0, 0, 1), vec3(1, 0, 0), vec3(4.0f));  // faces -y
    test::SceneBindings sb(s);
    vec3 aimed = meanCausticPower(sb);
    vec3 brute = fluxHittingSpheres(sb);
    EXPECT_NEAR(aimed.x, brute.x, 0.02 * brute.x);

    Scene t = sceneWithTargets({{vec3(0.3f, -2, 0.2f), 0.6f}});
    t.addSphereLight(vec3(0, 1, 0), 0.4f, vec3(6.0f));
    test::SceneBindings tb(t);
    vec3 aimedSphere = meanCausticPower(tb);
    vec3 bruteSphere = fluxHittingSpheres(tb);
    EXPECT_NEAR(aimedSphere.x, bruteSphere.x, 0.02 * bruteSphere.x);
}

TEST(DirectLight, SphereLightMatchesItsFluxAtADistance) {
    // Far from a sphere light the irradiance is Φ / (4π d²), as for a point light.
    Scene s;
    s.addSphereLight(vec3(0, 10, 0), 0.2f, vec3(100.0f));
    test::SceneBindings sb(s);
    Rng rng = rngCreate(0u, 0u, 2u, STREAM_CAMERA);
    double e = 0.0;
    for (int i = 0; i < kN / 4; ++i) {
        LightSample ls = sampleDirectLight(sb.bindings, sb.scene.lights[0], vec3(0), rng);
        e += ls.radiance.x * std::max(0.0f, ls.direction.y);
    }
    e /= kN / 4;
    EXPECT_NEAR(e, 100.0 / (4.0 * 3.14159265 * 100.0), 0.002 * e);
}

TEST(DirectLight, LightsBeyondTheFloatRangeSendNothing) {
    // A point or spot light farther from x than floats can square (a fuzzed scene's light at
    // 3.4e38) sends no light, and its sample's direction stays a unit vector, not 0 or NaN.
    for (bool spot : {false, true}) {
        Scene s;
        s.addPlane(vec3(0), vec3(0, 1, 0), s.addMaterial("m", makeDiffuse(vec3(0.5f))));
        if (spot) {
            s.addSpotLight(vec3(-3.5f, 3.5f, 3.4e38f), vec3(-2.7f, 1.9f, 1.9f), vec3(2.0f), 66.0f, 0.0f);
        } else {
            s.addPointLight(vec3(0.0f, 2e19f, 0.0f), vec3(1.0f));
        }
        test::SceneBindings sb(s);
        Rng rng = rngCreate(0u, 0u, 4u, STREAM_CAMERA);
        LightSample ls = sampleDirectLight(sb.bindings, sb.scene.lights[0], vec3(0), rng);
        EXPECT_EQ(ls.radiance, vec3(0.0f)) << (spot ? "spot" : "point");
        EXPECT_FLOAT_EQ(glm::length(ls.direction), 1.0f) << (spot ? "spot" : "point");
    }
}

TEST(DirectLight, SpotIntensityMatchesEmittedPower) {
    // Integrating the spot's intensity over the sphere returns Φ.
    Scene s;
    s.addSpotLight(vec3(0), vec3(0, 0, 1), vec3(7.0f), 40.0f, 25.0f);
    s.finalize();
    Rng rng = rngCreate(0u, 0u, 3u, 0u);
    double sum = 0.0;
    for (int i = 0; i < kN; ++i) {
        float u1 = rngNext(rng);
        float u2 = rngNext(rng);
        sum += pointIntensity(s.lights[0], sampleUniformSphere(u1, u2)).x * 4.0 * 3.14159265358979;
    }
    EXPECT_NEAR(sum / kN, 7.0, 0.05);
}

}  // namespace
}  // namespace photon

namespace photon {
namespace {

// A floor lit by a quad light overhead: far along the floor, shadow rays graze and their lifted
// origins must not carry them past the light's own surface, which would shadow the light itself.
TEST(DirectLight, AreaLightsDoNotShadowThemselvesAtGrazingAngles) {
    for (int kind = 0; kind < 2; ++kind) {
        Scene s;
        std::uint32_t floor = s.addMaterial("floor", makeDiffuse(vec3(0.5f)));
        s.addPlane(vec3(0.0f), vec3(0, 1, 0), floor);
        if (kind == 0) {
            s.addQuadLight(vec3(-1, 6, -1), vec3(2, 0, 0), vec3(0, 0, 2), vec3(100.0f));
        } else {
            s.addSphereLight(vec3(0, 6, 0), 0.5f, vec3(100.0f));
        }
        test::SceneBindings sb(s);
        for (float z : {-2.0f, -8.0f, -20.0f, -60.0f}) {
            Rng rng = rngCreate(1u, 0u, 1u, STREAM_CAMERA);
            vec3 x(0.5f, 0.0f, z);
            vec3 lit = directLight(sb.bindings, x, vec3(0, 1, 0), vec3(0, 1, 0), vec3(0, 1, 0), sb.scene.materials[floor], NONE, rng);
            EXPECT_GT(lit.x, 0.0f) << (kind == 0 ? "quad" : "sphere") << " light: floor at z = " << z << " sees none";
        }
    }
}

// Every type answers lightFlags once, and nothing else does.
TEST(LightTypes, EveryTypeHasFlagsAndANameAndNoOtherDoes) {
    for (uint type = 0; type < LIGHT_TYPE_COUNT; ++type) {
        EXPECT_NE(lightFlags(type), 0u) << lightTypeName(type);
    }
    EXPECT_EQ(lightFlags(LIGHT_TYPE_COUNT), 0u);
    EXPECT_THROW(lightTypeName(LIGHT_TYPE_COUNT), std::logic_error);
    EXPECT_EQ(lightFlags(LIGHT_ENVIRONMENT), LIGHT_FLAG_INFINITE);
    EXPECT_EQ(lightFlags(LIGHT_DIRECTIONAL), LIGHT_FLAG_DELTA_DIRECTION);
}

// A type the shared code does not know never reaches a kernel: finalize() refuses it.
TEST(Finalize, RefusesUnknownLightAndMaterialTypes) {
    Scene s;
    s.addPointLight(vec3(0), vec3(1.0f));
    s.lights[0].type = LIGHT_TYPE_COUNT;
    EXPECT_THROW(s.finalize(), std::logic_error);
    s.lights[0].type = LIGHT_ENVIRONMENT;  // the environment is the scene's, set by setEnvironment
    EXPECT_THROW(s.finalize(), std::logic_error);
    s.lights[0].type = LIGHT_POINT;
    Material odd = makeDiffuse(vec3(0.5f));
    odd.type = MATERIAL_TYPE_COUNT;
    s.addMaterial("odd", odd);
    EXPECT_THROW(s.finalize(), std::logic_error);
}

// Rays that leave the scene ask its infinite light, which emits no photons and is not sampled
// for direct light: it is not among the lights.
TEST(InfiniteLight, RaysThatMissSeeTheBackgroundAndNothingElseDoes) {
    Scene s;
    s.addPointLight(vec3(0), vec3(1.0f));
    s.setBackground(vec3(0.25f, 0.5f, 2.0f));
    test::SceneBindings sb(s);
    EXPECT_EQ(sb.scene.lights.size(), 1u);
    EXPECT_EQ(sb.bindings.params.scene.lightCount, 1u);
    ASSERT_EQ(sb.scene.infiniteLights.size(), 1u);
    EXPECT_EQ(sb.scene.infiniteLights[0].type, LIGHT_ENVIRONMENT);
    vec3 seen = infiniteRadiance(sb.bindings, vec3(0, 0, 1));
    EXPECT_EQ(seen, vec3(0.25f, 0.5f, 2.0f));
}

}  // namespace
}  // namespace photon
