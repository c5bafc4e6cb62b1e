// The eye pass, without recursion: a camera ray (jittered for anti-aliasing, through a thin lens
// for depth of field) follows mirrors and glass to the first non-specular surface, where direct
// light is computed with shadow rays and a HitPoint is left for the gather stage. At the first
// glass interfaces and mirror coats the path follows both branches (tracePixel); past them one of
// reflection and refraction is chosen with the Fresnel probability, and at a reflective surface
// its mirror coat or its base, each with its share of the weight: frames average the choices.
#ifndef PHOTON_SHARED_EYE_TRACE_H
#define PHOTON_SHARED_EYE_TRACE_H

#include "bsdf.h"
#include "dispersion.h"
#include "gather.h"
#include "lights.h"
#include "specular_split.h"
#include "surface.h"
#include "volume_estimate.h"

PH_NAMESPACE_BEGIN

// Camera ray through pixel (px, py); y grows downwards. Four draws unless FLAG_PIXEL_CENTER.
PH_FN Ray cameraRay(PH_IN(Camera) camera, uint px, uint py, uint width, uint height, uint flags, PH_INOUT(Rng) rng) {
    bool center = (flags & FLAG_PIXEL_CENTER) != 0u;
    float jx = 0.5f;
    float jy = 0.5f;
    if (!center) {
        jx = rngNext(rng);
        jy = rngNext(rng);
    }
    float sx = (2.0f * (float(px) + jx) / float(width) - 1.0f) * camera.tanHalfFovY * camera.aspect;
    float sy = (1.0f - 2.0f * (float(py) + jy) / float(height)) * camera.tanHalfFovY;
    vec3 direction = unitVector(camera.forward + sx * camera.right + sy * camera.up);
    vec3 origin = camera.position;
    if (!center && camera.lensRadius > 0.0f) {
        float u1 = rngNext(rng);
        float u2 = rngNext(rng);
        vec2 lens = camera.lensRadius * sampleUniformDisk(u1, u2);
        vec3 focus = origin + direction * (camera.focusDistance / dot(direction, camera.forward));
        origin = origin + lens.x * camera.right + lens.y * camera.up;
        direction = unitVector(focus - origin);
    }
    return makeRay(origin, direction, FLOAT_MAX);
}

// The inverse of cameraRay through a pinhole: where `point` appears on the image, as continuous
// pixel coordinates (x right, y down; pixel (px, py) spans [px, px + 1) × [py, py + 1), its centre
// at +0.5) and, in z, its depth along the view direction. z ≤ 0: the point is behind the camera
// and x, y mean nothing. A thin lens blurs points off the focus plane; their pinhole position is
// returned.
PH_FN vec3 projectToPixel(PH_IN(Camera) camera, vec3 point, uint width, uint height) {
    vec3 d = point - camera.position;
    float z = dot(d, camera.forward);
    float sx = dot(d, camera.right) / z;
    float sy = dot(d, camera.up) / z;
    float x = (sx / (camera.tanHalfFovY * camera.aspect) + 1.0f) * 0.5f * float(width);
    float y = (1.0f - sy / camera.tanHalfFovY) * 0.5f * float(height);
    return vec3(x, y, z);
}

// Whether a shadow ray from x (geometric normal ng, facing the ray) towards `point` reaches it.
PH_FN bool shadowRayReaches(BUF_PARAM vec3 x, vec3 ng, vec3 direction, vec3 point) {
    // The shadow ray runs from where it starts, lifted off the surface, to the point on the
    // light: measured from x instead, a grazing ray would end beyond the light's surface.
    vec3 origin = offsetRayOrigin(x, ng, direction);
    vec3 toLight = point - origin;
    float distance = sqrt(dot(toLight, toLight));
    return !traceOccluded(BUF_ARG origin, toLight * (1.0f / distance), distance * (1.0f - 1.0e-4f));
}

// Reflected direct light at x from the environment, by multiple importance sampling of its map
// and of the BSDF (Veach 1997, the power heuristic): one shadow ray each. The map finds a small
// bright sky or sun, the BSDF a glossy highlight of a broad one. Five draws. x lies in `medium`.
PH_FN vec3 environmentDirectLight(BUF_PARAM PH_IN(Light) light, vec3 x, vec3 ns, vec3 ng, vec3 wo, PH_IN(Material) m,
                                  uint medium, PH_INOUT(Rng) rng) {
    vec3 sum = vec3(0.0f);
    LightSample ls = sampleDirectLight(BUF_ARG light, x, rng);
    float cosine = dot(ns, ls.direction);
    if (cosine > 0.0f && dot(ng, ls.direction) > 0.0f && !isBlack(ls.radiance) &&
        shadowRayReaches(BUF_ARG x, ng, ls.direction, ls.point)) {
        float weight = powerHeuristic(ls.pdf, pdfBsdf(m, wo, ls.direction, ns));
        vec3 radiance = spectralFromRgb(BUF_ARG ls.radiance);
        if (medium != NONE) {
            radiance *= mediumTransmittance(BUF_ARG medium, x, ls.direction, FLOAT_MAX);
        }
        sum += evalBsdf(m, wo, ls.direction, ns) * radiance * (cosine * weight);
    }
    BsdfSample bs = sampleBsdf(m, wo, ng, ns, rng);
    vec3 wi = bs.direction;
    float cosI = dot(ns, wi);
    float pdf = pdfBsdf(m, wo, wi, ns);
    if (bs.lobe == LOBE_NONE || cosI <= 0.0f || dot(ng, wi) <= 0.0f || !(pdf > 0.0f)) {
        return sum;
    }
    vec3 radiance = environmentRadiance(BUF_ARG light, wi);
    vec3 far = x + wi * (2.0f * (length(x - boundingCenter(light)) + boundingRadius(light)));
    if (!isBlack(radiance) && shadowRayReaches(BUF_ARG x, ng, wi, far)) {
        float weight = powerHeuristic(pdf, environmentPdf(BUF_ARG light, wi));
        vec3 arriving = spectralFromRgb(BUF_ARG radiance);
        if (medium != NONE) {
            arriving *= mediumTransmittance(BUF_ARG medium, x, wi, FLOAT_MAX);
        }
        sum += evalBsdf(m, wo, wi, ns) * arriving * (cosI * weight / pdf);
    }
    return sum;
}

// Reflected direct light at x from every light, lightSamples shadow rays each (two for the
// environment). ns is the shading normal and ng the geometric one, both facing wo; light from
// behind the geometric surface is not reflected, and shadow rays leave from its side, through
// `medium` (NONE: none).
PH_FN vec3 directLight(BUF_PARAM vec3 x, vec3 ns, vec3 ng, vec3 wo, PH_IN(Material) m, uint medium, PH_INOUT(Rng) rng) {
    vec3 sum = vec3(0.0f);
    uint samples = BUF(params).lightSamples;
    for (uint l = 0u; l < BUF(params).scene.lightCount; ++l) {
        Light light = BUF(lights)[l];
        for (uint j = 0u; j < samples; ++j) {
            if (light.type == LIGHT_ENVIRONMENT) {
                sum += environmentDirectLight(BUF_ARG light, x, ns, ng, wo, m, medium, rng);
                continue;
            }
            LightSample ls = sampleDirectLight(BUF_ARG light, x, rng);
            float cosine = dot(ns, ls.direction);
            if (cosine <= 0.0f || dot(ng, ls.direction) <= 0.0f || isBlack(ls.radiance)) {
                continue;
            }
            if (shadowRayReaches(BUF_ARG x, ng, ls.direction, ls.point)) {
                vec3 radiance = spectralFromRgb(BUF_ARG ls.radiance);
                if (medium != NONE) {
                    radiance *= mediumTransmittance(BUF_ARG medium, x, ls.direction, length(ls.point - x));
                }
                sum += evalBsdf(m, wo, ls.direction, ns) * radiance * cosine;
            }
        }
    }
    return sum / float(max(samples, 1u));
}

PH_FN HitPoint emptyHitPoint() {
    HitPoint hp;
    hp.position = vec3(0.0f);
    hp.material = NONE;
    hp.weight = vec3(0.0f);
    hp.normal = 0u;
    hp.direct = vec3(0.0f);
    hp.outgoing = 0u;
    hp.albedo = vec3(0.0f);
    hp.geometricNormal = 0u;
    hp.metallic = 0.0f;
    hp.roughness = 0.0f;
    hp.channel = CHANNEL_ALL;
    hp.pathLength = 0.0f;
    hp.aovAlbedo = vec3(0.0f);
    hp.aovNormal = 0u;
    return hp;
}

// The hit point where an eye path ends: at x (hit.position) on material `material`, with the
// path's weight, the shading and geometric normals and the direction back along the path (all
// facing wo), and the textured values the gather stage cannot look up again.
PH_FN void endPathAt(PH_INOUT(HitPoint) hp, vec3 x, uint material, vec3 weight, vec3 ns, vec3 ng, vec3 wo,
                     PH_IN(Material) m) {
    hp.position = x;
    hp.material = material;
    hp.weight = weight;
    hp.normal = octEncode(ns);
    hp.geometricNormal = octEncode(ng);
    hp.outgoing = octEncode(wo);
    hp.albedo = m.albedo;
    hp.metallic = m.metallic;
    hp.roughness = m.roughness;
}

// The surface the auxiliary images describe (aov.h): the first one the path meets that is not a
// perfect mirror or glass, `travelled` from the camera along the path, its albedo times the
// path's weight through mirrors and glass up to it (before any choice between its own lobes, whose
// weights would make one frame's albedo several times the surface's). None (pathLength -1) if the
// path met an emitter first.
PH_FN void meetAovSurface(BUF_PARAM PH_INOUT(HitPoint) hp, vec3 weight, vec3 albedo, vec3 ns, float travelled) {
    if (hp.pathLength == 0.0f) {
        hp.pathLength = max(travelled, 1.0e-30f);  // a camera on the surface still met it
        hp.aovAlbedo = rgbFromSpectral(BUF_ARG weight * albedo);
        hp.aovNormal = octEncode(ns);
    }
}

// A probe of the traversal alone, for photon-bench (Aila and Laine's "primary rays"): the ray
// through the pixel's centre and its nearest hit, without shading. 1 if it hit anything.
PH_FN uint tracePrimaryRay(BUF_PARAM uint pixel) {
    uint width = BUF(params).width;
    Rng rng = rngCreate(pixel, 0u, 0u, STREAM_CAMERA);  // unused: no jitter through the centre
    Ray ray = cameraRay(BUF(params).camera, pixel % width, pixel / width, width, BUF(params).height, FLAG_PIXEL_CENTER, rng);
    return traceRay(BUF_ARG ray, QUERY_CLOSEST).kind != NONE ? 1u : 0u;
}

// The eye ray's way through its medium up to tHit (FLOAT_MAX: it leaves the scene): the light the
// medium scatters towards the eye joins `volume`, and the path's weight takes the transmittance.
PH_FN_OUTLINED void eyeRayThroughMedium(BUF_PARAM PH_INOUT(vec3) volume, PH_INOUT(vec3) weight, uint medium, PH_IN(Ray) ray,
                               float tHit) {
    Medium md = loadMedium(BUF_ARG medium);
    vec2 span = mediumSpan(md, ray.origin, ray.direction, tHit);
    if (span.x < span.y) {
        volume += weight * beamRadianceEstimate(BUF_ARG md, ray.origin, ray.direction, span);
        weight *= expNegative3(extinctionOf(md) * densityIntegral(BUF_ARG md, ray.origin, ray.direction, span.x, span.y));
    }
}

// A branch of an eye path set aside where the path split, traced once the branches before it end.
struct EyeBranch {
    vec3 origin; uint medium;
    vec3 direction; uint channel;
    vec3 weight; uint depth;  // the path's weight up to here, times the branch's share; its next depth
};

PH_FN EyeBranch makeEyeBranch(vec3 origin, vec3 direction, vec3 weight, uint medium, uint channel, uint depth) {
    EyeBranch b;
    b.origin = origin;
    b.medium = medium;
    b.direction = direction;
    b.channel = channel;
    b.weight = weight;
    b.depth = depth;
    return b;
}

// The photon estimates where a branch that leaves no hit point ends on a surface (x, with the
// normals facing wo, as endPathAt takes them): the radius estimate of each surface map, at once in
// the eye pass. Its radius holds BRANCH_NEIGHBOURS photons at the density about x (as sppm's first
// radius does), at most the frame's radius (GridParams.radius; under sppm the median of the pixels'
// radii), and shrinks from frame to frame as progressive photon mapping's (FrameParams.branchShrink):
// each frame's estimate is Knaus and Zwicker's, and the frames' mean converges. (The frame's radius
// alone blurred the caustic the glass ball reflects: the ball's error after 8 frames of the Cornell
// box at 320 × 240 was 18.9%, 10.4% with this one; 16, 32 and 128 photons measured 11.6, 10.6, 11.0.)
PH_FN_OUTLINED vec3 branchPhotonEstimate(BUF_PARAM vec3 x, uint material, vec3 ns, vec3 ng, vec3 wo, PH_IN(Material) m, float u) {
    HitPoint end = emptyHitPoint();
    endPathAt(end, x, material, vec3(1.0f), ns, ng, wo, m);
    Shading s = hitPointShading(BUF_ARG end);
    vec3 sum = vec3(0.0f);
    for (uint map = 0u; map < SURFACE_MAP_COUNT; ++map) {
        GridParams grid = BUF(params).grids[map];
        if (grid.photonCapacity != 0u && grid.radius > 0.0f) {
            float dense = cellDensityRadius(BUF_ARG grid, s.position, s.geometricNormal, BRANCH_NEIGHBOURS);
            float r = dense > 0.0f ? min(grid.radius, dense * BUF(params).branchShrink) : grid.radius;
            sum += estimateRadius(BUF_ARG grid, s, r, BUF(params).kernel, u);
        }
    }
    return sum;
}

// The interfaces where this frame's eye paths split. The final image's only, in the global map's
// direct mode (under final gather the global map holds direct light and caustics too): a branch
// that leaves no hit point adds its estimates to the hit point's `direct`, which the other views
// show apart from the maps.
PH_FN uint eyeSplitBudget(BUF_PARAM_ALONE) {
    bool splits = BUF(params).view == VIEW_FINAL && BUF(params).globalMode == GLOBAL_DIRECT;
    return splits ? min(BUF(params).eyeSplits, EYE_SPLITS_MAX) : 0u;
}

// The weight a branch carries, to tell which of two leads.
PH_FN float branchShare(vec3 weight) { return weight.x + weight.y + weight.z; }

// A pixel's eye path. At the first eyeSplits glass interfaces and mirror coats it meets (FrameParams),
// the path follows both branches, each with its share (specular_split.h): at glass the one with the
// larger share goes on at once and the other is set aside and traced after it; at a mirror coat the
// base ends the path there and the coat's reflection waits. The branch that leads at
// every split leaves the pixel's hit point (its sppm statistics, its auxiliary images: a surface that
// stays the same from frame to frame); every other branch adds its light, direct and from the
// photon maps (branchPhotonEstimate), to the hit point's `direct`. Past the splits, one branch is
// chosen at random, as everywhere in the photon pass.
PH_FN HitPoint tracePixel(BUF_PARAM uint pixel) {
    uint width = BUF(params).width;
    Rng rng = rngCreate(pixel, BUF(params).frameIndex, BUF(params).seed, STREAM_CAMERA);
    Ray ray = cameraRay(BUF(params).camera, pixel % width, pixel / width, width, BUF(params).height,
                        BUF(params).flags, rng);
    HitPoint hp = emptyHitPoint();
    vec3 weight = vec3(1.0f);
    uint channel = CHANNEL_ALL;
    bool emittersSampled = false;  // the last bounce's lobe took direct light by shadow rays
    float travelled = 0.0f;        // the path's length so far
    uint medium = BUF(params).scene.medium;
    vec3 volume = vec3(0.0f);      // light scattered towards the eye by media along the path
    uint splits = eyeSplitBudget(BUF_ARG_ALONE);
    bool visible = true;           // this branch leaves the hit point
    bool ended = false;
    EyeBranch pending[EYE_SPLITS_MAX];
    uint pendingCount = 0u;
    uint maxDepth = BUF(params).maxEyeDepth;
    for (uint depth = 0u;; ++depth) {
        if (ended || depth >= maxDepth) {
            if (visible) {
                hp.channel = channel;
            }
            if (pendingCount == 0u) {
                break;
            }
            pendingCount -= 1u;
            EyeBranch b = pending[pendingCount];
            ray = makeRay(b.origin, b.direction, FLOAT_MAX);
            weight = b.weight;
            medium = b.medium;
            channel = b.channel;
            depth = b.depth;
            emittersSampled = false;
            visible = false;
            ended = false;
        }
        Hit hit;
        bool hits = traceClosest(BUF_ARG ray, hit);
        if (PH_SCENE_HAS_MEDIA && medium != NONE) {
            eyeRayThroughMedium(BUF_ARG volume, weight, medium, ray, hits ? hit.t : FLOAT_MAX);
        }
        if (!hits) {
            // Seen by the camera or through mirrors and glass; after a glossy bounce, direct light
            // has counted an environment that lights the scene already.
            if (!(emittersSampled && BUF(params).scene.environmentLight != NONE)) {
                hp.direct += weight * spectralFromRgb(BUF_ARG infiniteRadiance(BUF_ARG ray.direction));
            }
            ended = true;
            continue;
        }
        travelled += hit.t;
        SurfacePoint sp = surfaceAt(BUF_ARG hit);
        Material m = sp.material;
        uint surface = materialFlags(m);
        vec3 wo = -ray.direction;
        weight *= volumeTransmittance(m, dot(wo, hit.normal), hit.t);
        meetDispersion(BUF_ARG m, channel, weight, rng);
        if ((surface & SURFACE_EMITS) != 0u) {
            // An emitter is no surface for the auxiliary images: its light is not its albedo
            // times what reaches it, and the denoiser must leave it as it is.
            if (visible && hp.pathLength == 0.0f) {
                hp.pathLength = -1.0f;
            }
            // Seen by the camera or through mirrors and glass; at diffuse surfaces direct light
            // counts the lights (area lights, emissive triangles) with shadow rays.
            bool sampled = emittersSampled && (m.type == MATERIAL_EMITTER || hit.kind == PRIM_TRIANGLE);
            if (dot(wo, hit.normal) > 0.0f && !sampled) {
                hp.direct += weight * m.emission;
            }
            if (m.type == MATERIAL_EMITTER) {
                ended = true;
                continue;
            }
        }
        float side = dot(wo, sp.geometricNormal) >= 0.0f ? 1.0f : -1.0f;
        vec3 ng = sp.geometricNormal * side;
        vec3 ns = sp.shadingNormal * side;
        if (m.type == MATERIAL_PBR) {
            // Direct light through every lobe shadow rays can find, whichever way the path goes
            // on; then the path ends at the stored lobes or follows a traced one.
            bool stores = (surface & SURFACE_STORES_PHOTONS) != 0u;
            if (stores || m.roughness >= PBR_DELTA_ALPHA) {
                if (visible) {
                    meetAovSurface(BUF_ARG hp, weight, m.albedo, ns, travelled);
                }
                hp.direct += weight * directLight(BUF_ARG hit.position, ns, ng, wo, m, medium, rng);
            }
            float pTraced = stores ? pbrTracedProbability(m, dot(wo, ns)) : 1.0f;
            if (stores && rngNext(rng) >= pTraced) {
                vec3 stored = weight / (1.0f - pTraced);
                if (visible) {
                    endPathAt(hp, hit.position, hit.material, stored, ns, ng, wo, m);
                } else {
                    hp.direct += stored * branchPhotonEstimate(BUF_ARG hit.position, hit.material, ns, ng, wo, m, rngNext(rng));
                }
                ended = true;
                continue;
            }
            BsdfSample bs = sampleBsdfLobes(m, wo, sp.geometricNormal, sp.shadingNormal, PBR_LOBES_TRACED, rng);
            if (bs.lobe == LOBE_NONE) {
                ended = true;
                continue;
            }
            weight *= bs.weight / pTraced;
            emittersSampled = m.roughness >= PBR_DELTA_ALPHA && dot(bs.direction, ng) > 0.0f;
            medium = mediumAcross(BUF_ARG medium, m, hit.kind, hit.normal, wo, bs.direction);
            ray = makeRay(offsetRayOrigin(hit.position, sp.geometricNormal, bs.direction), bs.direction, FLOAT_MAX);
            continue;
        }
        emittersSampled = false;
        bool ends = (surface & SURFACE_ENDS_EYE_PATHS) != 0u;
        if (ends && visible) {
            meetAovSurface(BUF_ARG hp, weight, m.albedo, ns, travelled);
        }
        bool splitsHere = splits > 0u && depth + 1u < maxDepth &&
                          (m.type == MATERIAL_GLASS || (surface & SURFACE_SPECULAR_COAT) != 0u);
        BsdfSample bs;
        if (splitsHere) {
            // Both branches: glass's reflection and refraction (the larger share goes on, the other
            // waits), or a mirror coat and the base under it.
            splits -= 1u;
            BsdfSample other;
            uint otherChannel = channel;
            if (m.type == MATERIAL_GLASS) {
                SpecularSplit split = splitDielectric(BUF_ARG m, wo, sp.geometricNormal, sp.shadingNormal, channel, rng);
                bool reflects = split.transmitted.lobe == LOBE_NONE ||
                                (split.reflected.lobe != LOBE_NONE &&
                                 branchShare(split.reflected.weight) > branchShare(split.transmitted.weight));
                bs = reflects ? split.reflected : split.transmitted;
                other = reflects ? split.transmitted : split.reflected;
                otherChannel = reflects ? split.transmittedChannel : channel;
                channel = reflects ? channel : split.transmittedChannel;
            } else {
                // The base keeps the hit point (it is the auxiliary images' surface too) and ends
                // the path here with its whole weight; the coat's reflection waits.
                if (visible) {
                    endPathAt(hp, hit.position, hit.material, weight, ns, ng, wo, m);
                } else {
                    hp.direct += weight * branchPhotonEstimate(BUF_ARG hit.position, hit.material, ns, ng, wo, m, rngNext(rng));
                }
                hp.direct += weight * directLight(BUF_ARG hit.position, ns, ng, wo, storedPart(m), medium, rng);
                other = absorbAcrossSurface(sampleMirrorCoat(m, wo, ns), sp.geometricNormal, side, false);
                other.weight = m.specular;
                bs.lobe = LOBE_NONE;
            }
            if (other.lobe != LOBE_NONE) {
                pending[pendingCount] = makeEyeBranch(offsetRayOrigin(hit.position, sp.geometricNormal, other.direction),
                                                      other.direction, weight * other.weight,
                                                      mediumAcross(BUF_ARG medium, m, hit.kind, hit.normal, wo, other.direction),
                                                      otherChannel, depth + 1u);
                pendingCount += 1u;
            }
        } else {
            // A mirror coat continues the path, or the surface's base ends it here.
            bool mirrorCoat = false;
            if ((surface & SURFACE_SPECULAR_COAT) != 0u) {
                float pMirror = specularLobeProbability(m);
                mirrorCoat = rngNext(rng) < pMirror;
                weight *= mirrorCoat ? vec3(1.0f) : vec3(1.0f / (1.0f - pMirror));
            }
            if (ends && !mirrorCoat) {
                if (visible) {
                    endPathAt(hp, hit.position, hit.material, weight, ns, ng, wo, m);
                } else {
                    hp.direct += weight * branchPhotonEstimate(BUF_ARG hit.position, hit.material, ns, ng, wo, m, rngNext(rng));
                }
                hp.direct += weight * directLight(BUF_ARG hit.position, ns, ng, wo, storedPart(m), medium, rng);
                ended = true;
                continue;
            }
            if (mirrorCoat) {
                bs = absorbAcrossSurface(sampleMirrorCoat(m, wo, ns), sp.geometricNormal, side, false);
            } else {
                bs = sampleBsdfAlongPath(BUF_ARG m, wo, sp.geometricNormal, sp.shadingNormal, channel, rng);
            }
        }
        if (bs.lobe == LOBE_NONE) {
            ended = true;
            continue;
        }
        weight *= bs.weight;
        medium = mediumAcross(BUF_ARG medium, m, hit.kind, hit.normal, wo, bs.direction);
        ray = makeRay(offsetRayOrigin(hit.position, sp.geometricNormal, bs.direction), bs.direction, FLOAT_MAX);
    }
    // The media's light joins the final image, or is all the volume view shows.
    if (BUF(params).view == VIEW_VOLUME) {
        hp.direct = volume;
        hp.material = NONE;
    } else if (BUF(params).view == VIEW_FINAL) {
        hp.direct += volume;
    }
    return hp;
}

PH_NAMESPACE_END

#endif
