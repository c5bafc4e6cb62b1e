// The gather stage: at each pixel's hit point, add the photon estimates to the direct light.
//   caustics: the caustic map, estimated at the hit point itself.
//   indirect: GLOBAL_DIRECT: the global map at the hit point (Jensen's "visualise the global map");
//             GLOBAL_FINAL_GATHER: gatherRays rays sampled from the BSDF, each followed through
//             mirrors and glass to a diffuse surface, where the global map (holding every diffuse
//             photon in this mode) gives the radiance towards the hit point. Rays that end on a
//             light add nothing: direct light and caustics are already counted.
#ifndef PHOTON_SHARED_GATHER_H
#define PHOTON_SHARED_GATHER_H

#include "dispersion.h"
#include "estimate.h"
#include "surface.h"

PH_NAMESPACE_BEGIN

// `channel`: the eye path's CHANNEL_*, which its gather rays continue.
PH_FN vec3 finalGather(BUF_PARAM PH_IN(Shading) s, uint estimator, uint eyeChannel, PH_INOUT(Rng) rng) {
    uint rays = BUF(params).gatherRays;
    vec3 sum = vec3(0.0f);
    for (uint g = 0u; g < rays; ++g) {
        BsdfSample bs = sampleBsdf(shadingMaterial(BUF_ARG s), s.wo, s.geometricNormal, s.normal, rng);
        if (bs.lobe == LOBE_NONE) {
            continue;
        }
        vec3 weight = bs.weight;
        uint channel = eyeChannel;
        Ray ray = makeRay(offsetRayOrigin(s.position, s.geometricNormal, bs.direction), bs.direction, FLOAT_MAX);
        for (uint depth = 0u; depth < BUF(params).maxEyeDepth; ++depth) {
            Hit hit;
            if (!traceClosest(BUF_ARG ray, hit)) {
                // It met the infinite light (lights.h, infiniteRadiance). Like a ray that ends on
                // a light it adds nothing: an infinite light is direct light where it is sampled
                // as one, and a uniform background lights nothing at all.
                break;
            }
            SurfacePoint sp = surfaceAt(BUF_ARG hit);
            Material m = sp.material;
            vec3 wo = -ray.direction;
            uint surface = materialFlags(m);
            weight *= volumeTransmittance(m, dot(wo, hit.normal), hit.t);
            meetDispersion(BUF_ARG m, channel, weight, rng);
            if ((surface & SURFACE_STORES_PHOTONS) != 0u) {
                float side = dot(wo, sp.geometricNormal) >= 0.0f ? 1.0f : -1.0f;
                Shading there = makeShading(hit.position, sp.shadingNormal * side, sp.geometricNormal * side, wo, hit.material, m);
                sum += weight * photonEstimate(BUF_ARG MAP_GLOBAL, there, estimator, rngNext(rng));
                break;
            }
            if ((surface & SURFACE_CAUSTIC_CASTER) == 0u) {
                break;
            }
            BsdfSample next = sampleBsdfAlongPath(BUF_ARG m, wo, sp.geometricNormal, sp.shadingNormal, channel, rng);
            if (next.lobe == LOBE_NONE) {
                break;
            }
            weight *= next.weight;
            ray = makeRay(offsetRayOrigin(hit.position, sp.geometricNormal, next.direction), next.direction, FLOAT_MAX);
        }
    }
    return sum / float(max(rays, 1u));
}

// Blue → cyan → green → yellow → red for t ∈ [0, 1].
PH_FN vec3 heatColor(float t) {
    float x = clamp(t, 0.0f, 1.0f) * 4.0f;
    return clamp(vec3(x - 2.0f, x < 2.0f ? x : 4.0f - x, 2.0f - x), vec3(0.0f), vec3(1.0f));
}

// (The volume view's light is in the hit point's `direct` alone: eye_trace.h.)
PH_FN bool viewShowsDirect(uint view) { return view == VIEW_FINAL || view == VIEW_DIRECT || view == VIEW_VOLUME; }

// Whether the view needs photon map `map` at all.
PH_FN bool viewShowsMap(uint view, uint map) {
    return view == VIEW_FINAL || (view == VIEW_CAUSTIC && map == MAP_CAUSTIC) || (view == VIEW_GLOBAL && map == MAP_GLOBAL);
}

// The shading point of a hit point (a mirror coat is not part of it: see storedPart).
PH_FN Shading hitPointShading(BUF_PARAM PH_IN(HitPoint) hp) {
    Material m = BUF(materials)[hp.material];
    m.albedo = hp.albedo;
    m.specular = spectralFromRgb(BUF_ARG m.specular);
    m.metallic = hp.metallic;
    m.roughness = hp.roughness;
    return makeShading(hp.position, octDecode(hp.normal), octDecode(hp.geometricNormal), octDecode(hp.outgoing),
                       hp.material, m);
}

// The pixel's radiance once the photon estimates (reflected radiance at the hit point) are known.
PH_FN vec3 gatherResult(PH_IN(HitPoint) hp, uint view, vec3 photons) {
    vec3 radiance = viewShowsDirect(view) ? hp.direct : vec3(0.0f);
    return hp.material == NONE ? radiance : radiance + hp.weight * photons;
}

// This frame's radiance through the pixel, for the given ESTIMATOR_* and GLOBAL_* mode. GPU
// backends pass compile-time constants, so that each variant carries only its own code.
PH_FN vec3 gatherPixel(BUF_PARAM uint pixel, uint estimator, uint globalMode) {
    HitPoint hp = BUF(hitPoints)[pixel];
    uint view = BUF(params).view;
    if (hp.material == NONE || view == VIEW_DIRECT) {
        return gatherResult(hp, view, vec3(0.0f));
    }
    if (view == VIEW_GRID) {
        float n = float(cellOccupancy(BUF_ARG MAP_GLOBAL, hp.position));
        return heatColor(n / (n + 32.0f) * 1.5f);
    }
    Shading s = hitPointShading(BUF_ARG hp);
    Rng rng = rngCreate(pixel, BUF(params).frameIndex, BUF(params).seed, STREAM_GATHER);
    float u = rngNext(rng);
    vec3 photons = vec3(0.0f);
    if (viewShowsMap(view, MAP_CAUSTIC)) {
        photons += photonEstimate(BUF_ARG MAP_CAUSTIC, s, estimator, u);
    }
    if (viewShowsMap(view, MAP_GLOBAL)) {
        if (globalMode == GLOBAL_FINAL_GATHER) {
            photons += finalGather(BUF_ARG s, estimator, hp.channel, rng);
        } else {
            photons += photonEstimate(BUF_ARG MAP_GLOBAL, s, estimator, u);
        }
    }
    return gatherResult(hp, view, photons);
}

// The same with the estimator and mode of the frame's parameters.
PH_FN vec3 gatherPixel(BUF_PARAM uint pixel) {
    return gatherPixel(BUF_ARG pixel, BUF(params).estimator, BUF(params).globalMode);
}

PH_NAMESPACE_END

#endif
