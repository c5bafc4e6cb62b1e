// Direct light for the eye pass: a sample towards a light from a point (with its solid-angle
// density, for multiple importance sampling with the BSDF), and the radiance of a ray that leaves
// the scene (the environment, or a background).
#ifndef PHOTON_SHARED_DIRECT_LIGHT_H
#define PHOTON_SHARED_DIRECT_LIGHT_H

#include "light_sources.h"

PH_NAMESPACE_BEGIN

// Direct-light sample: radiance arriving from `direction`, divided by the solid-angle density,
// and the point on the light it comes from (what a shadow ray must reach unobstructed). pdf: that
// density where other strategies could find the same light (the environment's, for multiple
// importance sampling), else 0.
struct LightSample {
    vec3 direction;
    vec3 point;
    vec3 radiance;
    float pdf;
};

// Direct-light sample towards `light` from x. Two draws, three for emissive triangles.
PH_FN LightSample sampleDirectLight(BUF_PARAM PH_IN(Light) light, vec3 x, PH_INOUT(Rng) rng) {
    float u1 = rngNext(rng);
    float u2 = rngNext(rng);
    LightSample ls;
    ls.radiance = vec3(0.0f);
    ls.direction = vec3(0.0f, 0.0f, 1.0f);
    ls.point = x;
    ls.pdf = 0.0f;
    PH_COVERS(LIGHT_TYPE_COUNT, 7u);
    switch (light.type) {
        case LIGHT_POINT:
        case LIGHT_SPOT: {
            vec3 d = pointPosition(light) - x;
            float dist2 = dot(d, d);
            if (!(dist2 < FLOAT_MAX)) {
                break;  // farther than floats reach: no light arrives, and d has no direction
            }
            ls.point = pointPosition(light);
            ls.direction = d * (1.0f / sqrt(dist2));
            ls.radiance = pointIntensity(light, -ls.direction) / dist2;
            break;
        }
        case LIGHT_DIRECTIONAL:
            // Irradiance E from one direction; the shadow ray runs out of the bounding sphere.
            ls.direction = -directionalDirection(light);
            ls.point = x + ls.direction * (2.0f * (length(x - boundingCenter(light)) + boundingRadius(light)));
            ls.radiance = directionalIrradiance(light);
            break;
        case LIGHT_SPHERE: {
            // Uniform over the cone that the sphere subtends: density 1 / (2π x).
            vec3 center = sphereCenter(light);
            float radius = sphereRadius(light);
            ls.point = center;
            float coneX = sphereConeX(x, center, radius);
            if (coneX >= 2.0f) {
                break;
            }
            vec3 axis = unitVector(center - x);
            ls.direction = sampleUniformCone(axis, coneX, u1, u2);
            float t = intersectSphere(makeRay(x, ls.direction, FLOAT_MAX), center, radius, FLOAT_MAX);
            ls.point = x + ls.direction * (t < FLOAT_MAX ? t : dot(center - x, ls.direction));
            ls.radiance = light.power * (INV_PI / light.area) * (TWO_PI * coneX);
            break;
        }
        case LIGHT_QUAD:
        case LIGHT_TRIANGLES: {
            // By area: density d² / (cosθ_light · area) in solid angle.
            float u0 = light.type == LIGHT_TRIANGLES ? rngNext(rng) : 0.0f;
            vec3 n;
            vec3 radiance;
            float areaPdf;
            sampleAreaLight(BUF_ARG light, u0, u1, u2, ls.point, n, radiance, areaPdf);
            vec3 d = ls.point - x;
            float dist2 = dot(d, d);
            ls.direction = d * (1.0f / sqrt(dist2));
            float cosLight = -dot(ls.direction, n);
            if (cosLight > 0.0f && dist2 > 0.0f) {
                ls.radiance = radiance * (cosLight / (areaPdf * dist2));
            }
            break;
        }
        case LIGHT_ENVIRONMENT: {
            // By the map; the shadow ray runs out of the bounding sphere.
            vec3 radiance = sampleEnvironment(BUF_ARG light, u1, u2, ls.direction, ls.pdf);
            ls.point = x + ls.direction * (2.0f * (length(x - boundingCenter(light)) + boundingRadius(light)));
            if (ls.pdf > 0.0f) {
                ls.radiance = radiance / ls.pdf;
            }
            break;
        }
    }
    return ls;
}

// The radiance that a ray leaving the scene along `direction` brings: the scene's infinite light
// (SceneInfo::infiniteLight), the environment. Eye paths ask it where they miss the scene. An
// environment that lights the scene is also lights[SceneInfo::environmentLight], sampled by
// photons and shadow rays; one that does not (a `background`) only colours what the camera
// sees, directly and through mirrors and glass.
PH_FN vec3 infiniteRadiance(BUF_PARAM vec3 direction) {
    Light light = BUF(infiniteLights)[BUF(params).scene.infiniteLight];
    PH_COVERS(LIGHT_TYPE_COUNT, 7u);
    switch (light.type) {
        case LIGHT_ENVIRONMENT:
            return environmentRadiance(BUF_ARG light, direction);
        case LIGHT_POINT:
        case LIGHT_SPOT:
        case LIGHT_SPHERE:
        case LIGHT_QUAD:
        case LIGHT_TRIANGLES:
        case LIGHT_DIRECTIONAL:
            break;  // not infinite (Scene::finalize puts none of these there)
    }
    return vec3(0.0f);
}

PH_NAMESPACE_END

#endif
