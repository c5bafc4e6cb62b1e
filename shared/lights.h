// Lights: photon emission (the global pass samples each light's own distribution; the caustic pass
// aims at specular objects, after Jensen's projection maps) and direct-light sampling for the eye
// pass. Emitted power and sampled radiance come from the same intensity functions, so direct light
// and photon estimates always agree on how bright a light is.
#ifndef PHOTON_SHARED_LIGHTS_H
#define PHOTON_SHARED_LIGHTS_H

#include "environment.h"
#include "intersect.h"
#include "light_types.h"
#include "rng.h"
#include "sampling.h"

PH_NAMESPACE_BEGIN

struct PhotonEmission {
    vec3 origin;
    vec3 direction;
    vec3 power;  // flux carried, before dividing by the number of paths and the light's pick probability
};

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

// A cone of directions: axis and 1 - cos of its half-angle (2: the whole sphere).
struct Cone {
    vec3 axis;
    float x;
};

// No photon: what a light that emits none (or no light) gives.
PH_FN PhotonEmission noEmission() {
    PhotonEmission e;
    e.origin = vec3(0.0f);
    e.direction = vec3(0.0f, 0.0f, 1.0f);
    e.power = vec3(0.0f);
    return e;
}

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
            ls.point = pointPosition(light);
            vec3 d = ls.point - x;
            float dist2 = dot(d, d);
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
