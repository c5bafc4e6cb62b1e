// The photon pass (Jensen 1996): a photon leaves a light, and at every surface it is either stored
// (non-specular surfaces), reflected or refracted, or absorbed by Russian roulette with its power
// rescaled so that the expected flux is unchanged. Each backend runs
//
//     PhotonPath path = startPhotonPath(index);
//     while (path alive) { Photon p; uint store = photonBounce(path, p); append p to the maps in `store`; }
//
// and decides only where the appended photons go in memory.
//
// What goes where:
//   caustic map: L S+ D paths (light, one or more mirror/glass bounces, then a diffuse surface).
//   volume map:  every scattering in a participating medium (medium.h), from the global pass;
//                a caustic-pass path that scatters ends there (the global pass has it), and a
//                path that scattered is no longer a caustic path.
//   global map:  GLOBAL_DIRECT mode: paths with at least one diffuse bounce before this one,
//                because the eye pass computes direct light with shadow rays and caustics from the
//                caustic map; GLOBAL_FINAL_GATHER mode: every diffuse hit, since gather rays need
//                the whole radiance at their hit points.
// Photons with index < globalPaths belong to the global pass; the rest to the caustic pass, which
// aims at the caustic targets (bounding spheres of finite mirror and glass objects). When the
// caustic pass runs (FLAG_SPLIT_CAUSTICS) the two passes divide the caustic paths between them by
// their first surface: the caustic pass owns the paths that first hit a target and drops any
// other, the global pass stores the rest (first hit on a mirror plane, a mirror coat, ...).
#ifndef PHOTON_SHARED_PHOTON_TRACE_H
#define PHOTON_SHARED_PHOTON_TRACE_H

#include "bsdf.h"
#include "dispersion.h"
#include "lights.h"
#include "medium.h"
#include "surface.h"

PH_NAMESPACE_BEGIN

struct PhotonPath {
    vec3 origin;
    uint flags;  // PATH_*
    vec3 direction;
    uint depth;  // surfaces hit and scatterings in media so far
    vec3 power;
    uint medium; // the Medium it travels through (NONE: none)
    Rng rng;
};

PH_FN bool photonPathAlive(PH_IN(PhotonPath) path) { return (path.flags & PATH_ALIVE) != 0u; }

// The identity of the photon stored by path `path` at bounce `bounce`: unique within a map.
PH_FN uint photonId(uint path, uint bounce) { return (path << PHOTON_BOUNCE_BITS) | bounce; }

PH_FN PhotonPath startPhotonPath(BUF_PARAM uint index) {
    PhotonPath path;
    path.rng = rngCreate(index, BUF(params).frameIndex, BUF(params).seed, STREAM_PHOTON);
    bool causticPass = index >= BUF(params).globalPaths;
    float pickProbability;
    uint lightIndex = pickLight(BUF_ARG rngNext(path.rng), pickProbability);
    Light light = BUF(lights)[lightIndex];
    PhotonEmission e;
    if (causticPass) {
        e = emitCausticPhoton(BUF_ARG light, path.rng);
    } else {
        e = emitPhoton(BUF_ARG light, path.rng);
    }
    float paths = float(causticPass ? BUF(params).causticPaths : BUF(params).globalPaths);
    path.origin = e.origin;
    path.direction = e.direction;
    path.power = spectralFromRgb(BUF_ARG e.power) / (paths * pickProbability);
    path.depth = 0u;
    path.medium = BUF(params).scene.medium;
    path.flags = withPathChannel(PATH_ALIVE | PATH_SPECULAR_ONLY | (causticPass ? PATH_CAUSTIC_PASS : 0u), CHANNEL_ALL);
    if (light.type == LIGHT_ENVIRONMENT) {
        path.flags |= PATH_FROM_ENVIRONMENT;
    }
    if (isBlack(path.power)) {
        path.flags = 0u;
    }
    return path;
}

// The photon's flight through its medium up to tHit (its next surface, FLOAT_MAX: none). True if
// it scattered (or ended) there: `store` then says whether `photon` goes to the volume map, and
// the path has moved on (Henyey–Greenstein, Russian roulette by the flight's weight) or ended.
// False if it flew through, its power weighted by the transmittance.
PH_FN_OUTLINED bool photonFlight(BUF_PARAM PH_INOUT(PhotonPath) path, float tHit, PH_OUT(Photon) photon, PH_OUT(uint) store) {
    store = 0u;
    Medium md = loadMedium(BUF_ARG path.medium);
    vec2 span = mediumSpan(md, path.origin, path.direction, tHit);
    if (!(span.x < span.y)) {
        return false;
    }
    FreeFlight flight = sampleFreeFlight(BUF_ARG md, path.origin, path.direction, span.x, span.y, path.rng);
    path.power *= flight.weight;
    if (!flight.scatters) {
        return false;
    }
    if ((path.flags & PATH_CAUSTIC_PASS) != 0u) {
        path.flags = 0u;
        return true;
    }
    vec3 x = path.origin + path.direction * flight.t;
    photon.position = x;
    photon.incoming = octEncode(-path.direction);
    photon.power = path.power;
    photon.id = photonId(path.rng.index, path.depth);
    store = STORE_VOLUME;
    float survival = min(1.0f, maxComponent(flight.weight));
    if (path.depth + 1u >= BUF(params).maxPhotonDepth || !(survival > 0.0f) || rngNext(path.rng) >= survival) {
        path.flags = 0u;
        return true;
    }
    path.power *= 1.0f / survival;
    float u1 = rngNext(path.rng);
    float u2 = rngNext(path.rng);
    path.direction = sampleHenyeyGreenstein(path.direction, md.g, u1, u2);
    path.origin = x;
    path.flags &= ~PATH_SPECULAR_ONLY;
    path.depth += 1u;
    return true;
}

// Follow the photon to its next surface or scattering. Fills `photon` and returns STORE_* bits saying which
// maps it belongs to (0: none), then moves the path on or ends it.
PH_FN uint photonBounce(BUF_PARAM PH_INOUT(PhotonPath) path, PH_OUT(Photon) photon) {
    Hit hit;
    bool hits = traceClosest(BUF_ARG makeRay(path.origin, path.direction, FLOAT_MAX), hit);
    if (path.depth == 0u && (path.flags & (PATH_FROM_ENVIRONMENT | PATH_CAUSTIC_PASS)) == PATH_FROM_ENVIRONMENT) {
        // How many of the environment's photons find the scene from where they start (the
        // global pass's: the caustic pass aims at its targets).
        PH_RESERVE_SLOT(BUF(counters)[COUNTER_ENVIRONMENT_PATHS]);
        if (hits) {
            PH_RESERVE_SLOT(BUF(counters)[COUNTER_ENVIRONMENT_HITS]);
        }
    }
    if (PH_SCENE_HAS_MEDIA && path.medium != NONE) {
        uint store;
        if (photonFlight(BUF_ARG path, hits ? hit.t : FLOAT_MAX, photon, store)) {
            return store;
        }
    }
    if (!hits) {
        path.flags = 0u;
        return 0u;
    }
    SurfacePoint sp = surfaceAt(BUF_ARG hit);
    Material m = sp.material;
    path.power *= volumeTransmittance(m, dot(path.direction, -hit.normal), hit.t);
    bool causticPass = (path.flags & PATH_CAUSTIC_PASS) != 0u;
    uint surface = materialFlags(m);
    if (path.depth == 0u && (surface & SURFACE_CAUSTIC_CASTER) != 0u && hit.kind != PRIM_PLANE) {
        path.flags |= PATH_FROM_TARGET;
    }
    if (causticPass && (path.flags & PATH_FROM_TARGET) == 0u) {
        path.flags = 0u;  // aimed at a target but something else was in the way: the global pass's
        return 0u;
    }
    uint store = 0u;
    if ((surface & SURFACE_STORES_PHOTONS) != 0u) {
        bool causticPath = (path.flags & PATH_SPECULAR_ONLY) != 0u && path.depth > 0u;
        if (causticPass) {
            store = causticPath ? STORE_CAUSTIC : 0u;
        } else {
            bool ownedByCausticPass = (BUF(params).flags & FLAG_SPLIT_CAUSTICS) != 0u &&
                                      (path.flags & PATH_FROM_TARGET) != 0u;
            if (causticPath && !ownedByCausticPass) {
                store |= STORE_CAUSTIC;
            }
            if (BUF(params).globalMode == GLOBAL_FINAL_GATHER || (!causticPath && path.depth > 0u)) {
                store |= STORE_GLOBAL;
            }
        }
        photon.position = hit.position;
        photon.incoming = octEncode(-path.direction);
        photon.power = path.power;
        photon.id = photonId(path.rng.index, path.depth);
    }
    if (path.depth + 1u >= BUF(params).maxPhotonDepth) {
        path.flags = 0u;
        return store;
    }
    uint channel = pathChannel(path.flags);
    meetDispersion(BUF_ARG m, channel, path.power, path.rng);
    BsdfSample bs = sampleBsdfAlongPath(BUF_ARG m, -path.direction, sp.geometricNormal, sp.shadingNormal, channel, path.rng);
    path.flags = withPathChannel(path.flags, channel);
    float survival = min(1.0f, maxComponent(bs.weight));
    // The caustic pass ends where its path stops being specular.
    bool leavesCausticPass = causticPass && bs.lobe != LOBE_SPECULAR;
    if (bs.lobe == LOBE_NONE || leavesCausticPass || !(survival > 0.0f) || rngNext(path.rng) >= survival) {
        path.flags = 0u;
        return store;
    }
    path.power *= bs.weight / survival;
    if (bs.lobe != LOBE_SPECULAR) {
        path.flags &= ~PATH_SPECULAR_ONLY;
    }
    path.medium = mediumAcross(BUF_ARG path.medium, m, hit.kind, hit.normal, -path.direction, bs.direction);
    path.origin = offsetRayOrigin(hit.position, hit.normal, bs.direction);
    path.direction = bs.direction;
    path.depth += 1u;
    return store;
}

// The next slot of map `map`; slots beyond its capacity are counted but not written, so that the
// host learns how much room the frame needed.
PH_FN void appendPhoton(BUF_PARAM uint map, PH_IN(Photon) photon) {
    uint slot = PH_RESERVE_SLOT(BUF(counters)[COUNTER_STORED + map]);
    if (slot < BUF(params).grids[map].photonCapacity) {
        BUF(photons)[BUF(params).grids[map].photonOffset + slot] = photon;
    }
}

// Photons of one bounce into the maps that `store` names.
PH_FN void appendStored(BUF_PARAM uint store, PH_IN(Photon) photon) {
    if ((store & STORE_GLOBAL) != 0u) {
        appendPhoton(BUF_ARG MAP_GLOBAL, photon);
    }
    if ((store & STORE_CAUSTIC) != 0u) {
        appendPhoton(BUF_ARG MAP_CAUSTIC, photon);
    }
    if ((store & STORE_VOLUME) != 0u) {
        appendPhoton(BUF_ARG MAP_VOLUME, photon);
    }
}

// STAGE_TRACE_PHOTONS, for one path index in [0, globalPaths + causticPaths). A path's random
// numbers and photon ids come from its index alone, so renderers that split a frame's paths
// between them (FrameParams.pathFirst, pathCount) trace, together, the photons one would.
PH_FN void tracePhotonPath(BUF_PARAM uint index) {
    PhotonPath path = startPhotonPath(BUF_ARG index);
    while (photonPathAlive(path)) {
        Photon photon;
        uint store = photonBounce(BUF_ARG path, photon);
        appendStored(BUF_ARG store, photon);
    }
}

// The i-th path of this renderer's share of the frame.
PH_FN void traceSharedPhotonPath(BUF_PARAM uint i) {
    if (i < BUF(params).pathCount) {
        tracePhotonPath(BUF_ARG BUF(params).pathFirst + i);
    }
}

// STAGE_TRACE_PHOTONS on a GPU: a pool of invocations, each taking the share's next path
// (COUNTER_PATHS_TAKEN) whenever its own ends. One path an invocation keeps a warp's lanes idle
// while its longest path goes on: paths end by Russian roulette after 1 to maxPhotonDepth
// bounces, and the caustic pass's paths through a glass mesh are the longest. Taking new paths
// keeps the lanes bouncing (path regeneration: Novák, Havran and Dachsbacher 2010). The photons
// are tracePhotonPath's over every path of the share; only the order they are appended in
// changes (and the deterministic maps' canonical order does not).
PH_FN void tracePhotonPool(BUF_PARAM_ALONE) {
    PhotonPath path;
    path.flags = 0u;
    for (;;) {
        if (!photonPathAlive(path)) {
            uint i = PH_RESERVE_SLOT(BUF(counters)[COUNTER_PATHS_TAKEN]);
            if (i >= BUF(params).pathCount) {
                return;
            }
            path = startPhotonPath(BUF_ARG BUF(params).pathFirst + i);
        }
        // Lanes that took a path bounce with those that went on, in the same pass of the loop.
        if (photonPathAlive(path)) {
            Photon photon;
            uint store = photonBounce(BUF_ARG path, photon);
            appendStored(BUF_ARG store, photon);
        }
    }
}

PH_NAMESPACE_END

#endif
