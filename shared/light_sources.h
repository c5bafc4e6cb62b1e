// Where light leaves a light, for both the photon passes and the eye pass's direct light: which
// light (picked by power), a point or spot light's intensity in a direction, a point on an area
// light, and the start of a parallel photon. Emitted power and sampled radiance come from these
// same functions, so direct light and photon estimates always agree on how bright a light is.
#ifndef PHOTON_SHARED_LIGHT_SOURCES_H
#define PHOTON_SHARED_LIGHT_SOURCES_H

#include "environment.h"
#include "intersect.h"
#include "light_types.h"
#include "rng.h"
#include "sampling.h"

PH_NAMESPACE_BEGIN

// The light that u ∈ [0, 1) picks, in proportion to power, and the probability of picking it.
PH_FN uint pickLight(BUF_PARAM float u, PH_OUT(float) probability) {
    uint last = BUF(params).scene.lightCount - 1u;
    for (uint i = 0u; i < last; ++i) {
        if (u < BUF(lights)[i].pickCdf) {
            probability = BUF(lights)[i].pickProbability;
            return i;
        }
    }
    probability = BUF(lights)[last].pickProbability;
    return last;
}

// Smooth spot falloff over x = 1 - cosθ: 1 inside spotInner, 0 beyond spotOuter.
PH_FN float spotFalloff(PH_IN(Light) light, float x) {
    if (x >= light.spotOuter) {
        return 0.0f;
    }
    if (x <= light.spotInner) {
        return 1.0f;
    }
    float s = (light.spotOuter - x) / (light.spotOuter - light.spotInner);
    return s * s * (3.0f - 2.0f * s);
}

// Radiant intensity [W/sr] of a point or spot light in the unit direction dir.
PH_FN vec3 pointIntensity(PH_IN(Light) light, vec3 dir) {
    PH_COVERS(LIGHT_TYPE_COUNT, 7u);
    switch (light.type) {
        case LIGHT_SPOT: {
            float falloff = spotFalloff(light, oneMinusCos(dir, spotAxis(light)));
            return light.power * (falloff / (TWO_PI * light.spotOuter * light.falloffMean));
        }
        case LIGHT_POINT:
            if (light.profile == EMIT_HEMISPHERE) {
                return light.power * (max(0.0f, dot(dir, hemisphereAxis(light))) * INV_PI);
            }
            return light.power * INV_FOUR_PI;
        case LIGHT_SPHERE:
        case LIGHT_QUAD:
        case LIGHT_TRIANGLES:
        case LIGHT_DIRECTIONAL:
        case LIGHT_ENVIRONMENT:
            break;  // no point source: nothing calls this for them
    }
    return vec3(0.0f);
}

// The emissive triangle of a LIGHT_TRIANGLES light that u ∈ [0, 1) picks, in proportion to power
// (a binary search of their cdf; the last one's is 1).
PH_FN uint pickEmitter(BUF_PARAM PH_IN(Light) light, float u) {
    uint lo = light.emitterFirst;
    uint hi = light.emitterFirst + light.emitterCount - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (u < BUF(emissiveTriangles)[mid].cdf) {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}

// A point on an area light and the light's front normal there. Sphere and quad lights: uniform by
// area, radiance Φ / (π · area). Emissive triangles: one picked by power (u0), then uniform on it;
// its material's emission. areaPdf is the density of the point per unit area of the light.
PH_FN void sampleAreaLight(BUF_PARAM PH_IN(Light) light, float u0, float u1, float u2, PH_OUT(vec3) p, PH_OUT(vec3) n,
                           PH_OUT(vec3) radiance, PH_OUT(float) areaPdf) {
    p = vec3(0.0f);
    n = vec3(0.0f, 0.0f, 1.0f);
    radiance = vec3(0.0f);
    areaPdf = 1.0f;
    PH_COVERS(LIGHT_TYPE_COUNT, 7u);
    switch (light.type) {
        case LIGHT_TRIANGLES: {
            EmissiveTriangle e = BUF(emissiveTriangles)[pickEmitter(BUF_ARG light, u0)];
            Triangle tri = BUF(triangles)[e.triangle];
            float su = sqrt(u1);
            p = tri.v0 * (1.0f - su) + tri.v1 * (su * (1.0f - u2)) + tri.v2 * (su * u2);
            n = unitVector(cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
            radiance = triangleEmission(BUF_ARG tri, su * (1.0f - u2), su * u2);
            areaPdf = e.probability / e.area;
            break;
        }
        case LIGHT_SPHERE:
            radiance = light.power * (INV_PI / light.area);
            areaPdf = 1.0f / light.area;
            n = sampleUniformSphere(u1, u2);
            p = sphereCenter(light) + sphereRadius(light) * n;
            break;
        case LIGHT_QUAD:
            radiance = light.power * (INV_PI / light.area);
            areaPdf = 1.0f / light.area;
            n = quadNormal(light);
            p = quadCorner(light) + u1 * quadEdgeU(light) + u2 * quadEdgeV(light);
            break;
        case LIGHT_POINT:
        case LIGHT_SPOT:
        case LIGHT_DIRECTIONAL:
        case LIGHT_ENVIRONMENT:
            break;  // no area: isAreaLight() is false, nothing calls this for them
    }
}

// The start of a parallel photon travelling along `travel` through point q of the unit disk: on
// the disk of the scene's bounding sphere (centre, radius) that faces it, behind everything in
// the scene (directional lights; the environment, per direction).
PH_FN vec3 parallelOrigin(vec3 center, float radius, vec3 travel, vec2 q) {
    return center + localToWorld(vec3(q.x, q.y, -1.001f), travel) * radius;
}

PH_NAMESPACE_END

#endif
