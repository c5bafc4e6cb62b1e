// Photon emission of the caustic pass, aimed at the specular objects after Jensen's projection
// maps: each photon's direction is drawn from the cones (or, for parallel light, the disks) that
// hold the caustic targets, clipped to what the light emits into, and weighted so that the flux
// each target receives is the light's own.
#ifndef PHOTON_SHARED_CAUSTIC_AIMING_H
#define PHOTON_SHARED_CAUSTIC_AIMING_H

#include "emission.h"

PH_NAMESPACE_BEGIN

// A cone of directions: axis and 1 - cos of its half-angle (2: the whole sphere).
struct Cone {
    vec3 axis;
    float x;
};

// 1 - cos(α + β) from xa = 1 - cos α and xb = 1 - cos β, for α + β ≤ π.
PH_FN float oneMinusCosSum(float xa, float xb) {
    float sa = sqrt(max(0.0f, xa * (2.0f - xa)));
    float sb = sqrt(max(0.0f, xb * (2.0f - xb)));
    return xa + xb - xa * xb + sa * sb;
}

// The cone the light emits into from a point on it (normal n for area lights). False: everywhere.
PH_FN bool emitterCone(PH_IN(Light) light, vec3 n, PH_OUT(Cone) cone) {
    cone.axis = n;
    cone.x = 1.0f;
    PH_COVERS(LIGHT_TYPE_COUNT, 7u);
    switch (light.type) {
        case LIGHT_SPOT:
            cone.axis = spotAxis(light);
            cone.x = light.spotOuter;
            return true;
        case LIGHT_POINT:
            cone.axis = hemisphereAxis(light);
            return light.profile == EMIT_HEMISPHERE;
        case LIGHT_SPHERE:
        case LIGHT_QUAD:
        case LIGHT_TRIANGLES:
            return true;  // the hemisphere about n
        case LIGHT_DIRECTIONAL:
            cone.axis = directionalDirection(light);
            cone.x = 0.0f;
            return true;  // one direction (its caustic photons are aimed by emitParallelCausticPhoton)
        case LIGHT_ENVIRONMENT:
            return false;  // from everywhere (its caustic photons are aimed by emitParallelCausticPhoton)
    }
    return false;  // no such type (Scene::finalize refuses it)
}

// The cone from `origin` that holds caustic target t, clipped to the emitter's cone: weight 0
// when the light sends nothing there, the emitter's own cone when it lies inside the target's.
// The weight is proportional to the cone's solid angle.
PH_FN Cone causticCone(vec3 origin, PH_IN(CausticTarget) t, bool clipped, PH_IN(Cone) emitter,
                       PH_OUT(float) weight) {
    Cone c;
    c.x = sphereConeX(origin, t.center, t.radius);
    c.axis = c.x >= 2.0f ? vec3(0.0f, 0.0f, 1.0f) : unitVector(t.center - origin);
    weight = c.x;
    if (!clipped) {
        return c;
    }
    if (c.x >= 2.0f) {
        weight = emitter.x;
        return emitter;
    }
    float between = oneMinusCos(c.axis, emitter.axis);
    if (emitter.x + c.x <= 2.0f && between >= oneMinusCosSum(emitter.x, c.x)) {
        weight = 0.0f;  // disjoint
    } else if (between + emitter.x <= 2.0f && oneMinusCosSum(between, emitter.x) <= c.x) {
        weight = emitter.x;  // the emitter's cone lies inside the target's
        return emitter;
    }
    return c;
}

// Photon of the caustic pass of parallel light along `travel` of irradiance E (a directional
// light's; the environment's L / pdf(ω) for a direction it drew): its start is drawn from the
// mixture of the targets' disks as the light sees them (projected along its direction, each
// weighted by its area), and its power is irradiance / mixture density, which keeps it unbiased.
PH_FN PhotonEmission emitParallelCausticPhoton(BUF_PARAM vec3 center, float radius, vec3 travel, vec3 irradiance,
                                               float u1, float u2, float u3) {
    PhotonEmission e;
    e.direction = travel;
    e.origin = center;
    e.power = vec3(0.0f);
    uint count = BUF(params).scene.targetCount;
    float total = 0.0f;
    for (uint k = 0u; k < count; ++k) {
        total += BUF(targets)[k].radius * BUF(targets)[k].radius;
    }
    if (!(total > 0.0f)) {
        return e;
    }
    float pick = u1 * total;
    uint chosen = count - 1u;
    for (uint k = 0u; k < count; ++k) {
        float w = BUF(targets)[k].radius * BUF(targets)[k].radius;
        if (pick < w) {
            chosen = k;
            break;
        }
        pick -= w;
    }
    // The target's centre projected onto the light's start disk, in its unit coordinates.
    CausticTarget t = BUF(targets)[chosen];
    vec3 rel = (t.center - center) * (1.0f / radius);
    vec3 axisX = localToWorld(vec3(1.0f, 0.0f, 0.0f), e.direction);
    vec3 axisY = localToWorld(vec3(0.0f, 1.0f, 0.0f), e.direction);
    vec2 q = vec2(dot(rel, axisX), dot(rel, axisY)) + sampleUniformDisk(u2, u3) * (t.radius / radius);
    float pdf = 0.0f;  // per unit area of the start disk, in scene units
    for (uint k = 0u; k < count; ++k) {
        CausticTarget tk = BUF(targets)[k];
        vec3 rk = (tk.center - center) * (1.0f / radius);
        vec2 d = q - vec2(dot(rk, axisX), dot(rk, axisY));
        float rr = tk.radius / radius;
        if (k == chosen || dot(d, d) <= rr * rr) {
            pdf += (tk.radius * tk.radius / total) / (PI * tk.radius * tk.radius);
        }
    }
    e.origin = parallelOrigin(center, radius, travel, q);
    e.power = irradiance / pdf;  // irradiance / density
    return e;
}

// Photon of the caustic pass of a directional light or the environment (a direction drawn from
// its map first). Three draws, five for the environment.
PH_FN PhotonEmission emitParallelLightCausticPhoton(BUF_PARAM PH_IN(Light) light, PH_INOUT(Rng) rng) {
    float u1 = rngNext(rng);
    float u2 = rngNext(rng);
    float u3 = rngNext(rng);
    vec3 travel = directionalDirection(light);
    vec3 irradiance = vec3(0.0f);
    if (light.type == LIGHT_ENVIRONMENT) {
        float v1 = rngNext(rng);
        float v2 = rngNext(rng);
        vec3 toward;
        float pdf;
        vec3 radiance = sampleEnvironment(BUF_ARG light, v1, v2, toward, pdf);
        if (!(pdf > 0.0f)) {
            return noEmission();
        }
        travel = -toward;
        PH_PRECISE vec3 e = radiance / pdf;
        irradiance = e;
    } else {
        irradiance = directionalIrradiance(light);
    }
    return emitParallelCausticPhoton(BUF_ARG boundingCenter(light), boundingRadius(light), travel, irradiance, u1, u2, u3);
}

// Photon of the caustic pass from a point or area light: its direction is drawn from the mixture
// of cones towards the specular objects, and its power is intensity / mixture density, which
// keeps it unbiased. Five draws, six for emissive triangles.
PH_FN PhotonEmission emitConeCausticPhoton(BUF_PARAM PH_IN(Light) light, PH_INOUT(Rng) rng) {
    float u1 = rngNext(rng);
    float u2 = rngNext(rng);
    float u3 = rngNext(rng);
    float u4 = rngNext(rng);
    float u5 = rngNext(rng);
    PhotonEmission e;
    // Point and spot lights emit from their position; area lights from a point drawn below.
    vec3 n = light.type == LIGHT_SPOT ? spotAxis(light) : hemisphereAxis(light);
    e.origin = pointPosition(light);
    e.direction = n;
    e.power = vec3(0.0f);
    vec3 radiance = vec3(0.0f);
    float areaPdf = 1.0f;
    if (isAreaLight(light)) {
        float u0 = light.type == LIGHT_TRIANGLES ? rngNext(rng) : 0.0f;
        vec3 p;
        sampleAreaLight(BUF_ARG light, u0, u1, u2, p, n, radiance, areaPdf);
        e.origin = offsetRayOrigin(p, n, n);
    }
    Cone emitter;
    bool clipped = emitterCone(light, n, emitter);
    uint count = BUF(params).scene.targetCount;
    float total = 0.0f;
    for (uint k = 0u; k < count; ++k) {
        float w;
        causticCone(e.origin, BUF(targets)[k], clipped, emitter, w);
        total += w;
    }
    if (!(total > 0.0f)) {
        return e;
    }
    float pick = u3 * total;
    uint chosen = count - 1u;
    Cone cone;
    cone.axis = n;
    cone.x = 2.0f;
    for (uint k = 0u; k < count; ++k) {
        float w;
        Cone c = causticCone(e.origin, BUF(targets)[k], clipped, emitter, w);
        if (w > 0.0f) {
            cone = c;
            chosen = k;
            if (pick < w) {
                break;
            }
            pick -= w;
        }
    }
    e.direction = sampleUniformCone(cone.axis, cone.x, u4, u5);
    float pdf = 0.0f;
    for (uint k = 0u; k < count; ++k) {
        float w;
        Cone c = causticCone(e.origin, BUF(targets)[k], clipped, emitter, w);
        if (w > 0.0f && (k == chosen || oneMinusCos(e.direction, c.axis) <= c.x)) {
            pdf += (w / total) * uniformConePdf(c.x);
        }
    }
    vec3 intensity;
    if (isAreaLight(light)) {
        // The radiant intensity of the light's whole area as seen from this point: L cosθ / areaPdf.
        intensity = radiance * (max(0.0f, dot(e.direction, n)) / areaPdf);
    } else {
        intensity = pointIntensity(light, e.direction);
    }
    e.power = intensity / pdf;
    return e;
}

// Photon of the caustic pass, aimed at the specular objects.
PH_FN PhotonEmission emitCausticPhoton(BUF_PARAM PH_IN(Light) light, PH_INOUT(Rng) rng) {
    PH_COVERS(LIGHT_TYPE_COUNT, 7u);
    switch (light.type) {
        case LIGHT_POINT:
        case LIGHT_SPOT:
        case LIGHT_SPHERE:
        case LIGHT_QUAD:
        case LIGHT_TRIANGLES:
            return emitConeCausticPhoton(BUF_ARG light, rng);
        case LIGHT_DIRECTIONAL:
        case LIGHT_ENVIRONMENT:
            return emitParallelLightCausticPhoton(BUF_ARG light, rng);
    }
    return noEmission();
}

PH_NAMESPACE_END

#endif
