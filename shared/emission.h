// Photon emission of the global pass: each light's photons drawn from its own emission
// distribution (points and spots by intensity, area lights by area and cosine, parallel light
// over the scene's bounding sphere, the environment by its map over the bounding box's faces).
#ifndef PHOTON_SHARED_EMISSION_H
#define PHOTON_SHARED_EMISSION_H

#include "light_sources.h"

PH_NAMESPACE_BEGIN

struct PhotonEmission {
    vec3 origin;
    vec3 direction;
    vec3 power;  // flux carried, before dividing by the number of paths and the light's pick probability
};

// No photon: what a light that emits none (or no light) gives.
PH_FN PhotonEmission noEmission() {
    PhotonEmission e;
    e.origin = vec3(0.0f);
    e.direction = vec3(0.0f, 0.0f, 1.0f);
    e.power = vec3(0.0f);
    return e;
}

// A photon of the environment: a direction by the map (u1, u2), then a start on the faces of the
// scene's bounding box that face it, uniform in the plane across the direction (Dammertz and
// Hanika's alternative to pbrt-v4's disk of the bounding sphere: every photon enters the bounds,
// where a disk wastes its rim). A face is picked in proportion to its area seen along the
// direction (u3, whose remainder is one coordinate on the face; u4 the other). The start density
// is 1 / the box's projected area A, so the flux is L A / pdf(ω).
PH_FN PhotonEmission emitEnvironmentPhoton(BUF_PARAM PH_IN(Light) light, float u1, float u2, float u3, float u4) {
    PhotonEmission e = noEmission();
    vec3 toward;
    float pdf;
    vec3 radiance = sampleEnvironment(BUF_ARG light, u1, u2, toward, pdf);
    vec3 h = boundsHalfExtent(light);
    // Each axis's face that the photon enters by, and its area seen along the direction.
    vec3 seen = vec3(h.y * h.z, h.x * h.z, h.x * h.y) * abs(toward) * 4.0f;
    float projected = seen.x + seen.y + seen.z;
    if (!(pdf > 0.0f) || !(projected > 0.0f)) {
        return e;
    }
    vec3 side = vec3(toward.x >= 0.0f ? 1.0f : -1.0f, toward.y >= 0.0f ? 1.0f : -1.0f, toward.z >= 0.0f ? 1.0f : -1.0f);
    float pick = u3 * projected;
    vec3 p;
    if (pick < seen.x) {
        float a = pick / seen.x;
        p = vec3(side.x, 2.0f * a - 1.0f, 2.0f * u4 - 1.0f);
    } else if (pick < seen.x + seen.y) {
        float a = (pick - seen.x) / seen.y;
        p = vec3(2.0f * a - 1.0f, side.y, 2.0f * u4 - 1.0f);
    } else {
        float a = clamp((pick - seen.x - seen.y) / seen.z, 0.0f, 1.0f);
        p = vec3(2.0f * a - 1.0f, 2.0f * u4 - 1.0f, side.z);
    }
    e.direction = -toward;
    // Started a little outside the face, back along its own ray: nothing on the face is missed.
    e.origin = boundingCenter(light) + p * h + toward * (1.0e-3f * boundingRadius(light));
    PH_PRECISE vec3 power = radiance * (projected / pdf);
    e.power = power;
    return e;
}

// An area light's photon: a point by area ((u3, u4); u0 picks an emissive triangle), a direction
// cosine-weighted about its normal (u1, u2).
PH_FN PhotonEmission emitAreaPhoton(BUF_PARAM PH_IN(Light) light, float u0, float u1, float u2, float u3,
                                    float u4) {
    vec3 n;
    vec3 p;
    vec3 radiance;
    float areaPdf;
    sampleAreaLight(BUF_ARG light, u0, u3, u4, p, n, radiance, areaPdf);
    PhotonEmission e;
    e.direction = localToWorld(sampleCosineHemisphere(u1, u2), n);
    e.origin = offsetRayOrigin(p, n, n);
    // A Lambertian emitter sends πL per unit area; over the area density that is the flux.
    e.power = radiance * (PI / areaPdf);
    return e;
}

// Photon of the global pass, drawn from the light's own emission distribution. Four draws, five
// for emissive triangles.
PH_FN PhotonEmission emitPhoton(BUF_PARAM PH_IN(Light) light, PH_INOUT(Rng) rng) {
    float u1 = rngNext(rng);
    float u2 = rngNext(rng);
    float u3 = rngNext(rng);
    float u4 = rngNext(rng);
    PhotonEmission e = noEmission();
    PH_COVERS(LIGHT_TYPE_COUNT, 7u);
    switch (light.type) {
        case LIGHT_POINT:
            e.origin = pointPosition(light);
            e.power = light.power;
            if (light.profile == EMIT_HEMISPHERE) {
                e.direction = localToWorld(sampleCosineHemisphere(u1, u2), hemisphereAxis(light));
            } else {
                e.direction = sampleUniformSphere(u1, u2);
            }
            break;
        case LIGHT_SPOT: {
            float x = u1 * light.spotOuter;
            e.origin = pointPosition(light);
            e.direction = directionAroundAxis(spotAxis(light), x, u2);
            e.power = light.power * (spotFalloff(light, x) / light.falloffMean);
            break;
        }
        case LIGHT_DIRECTIONAL:
            e.direction = directionalDirection(light);
            e.origin = parallelOrigin(boundingCenter(light), boundingRadius(light), e.direction, sampleUniformDisk(u1, u2));
            e.power = light.power;
            break;
        case LIGHT_ENVIRONMENT:
            e = emitEnvironmentPhoton(BUF_ARG light, u1, u2, u3, u4);
            break;
        case LIGHT_SPHERE:
        case LIGHT_QUAD:
            e = emitAreaPhoton(BUF_ARG light, 0.0f, u1, u2, u3, u4);
            break;
        case LIGHT_TRIANGLES: {
            float u0 = rngNext(rng);  // which triangle
            e = emitAreaPhoton(BUF_ARG light, u0, u1, u2, u3, u4);
            break;
        }
    }
    return e;
}

PH_NAMESPACE_END

#endif
