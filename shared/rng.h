// Counter-based random numbers: every draw is a hash of (index, frame, seed ^ stream, counter),
// so any backend, thread layout or draw order across threads yields the same numbers.
// The hash is pcg4d (Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020): a
// bijection of 128 bits, so no two (index, frame, stream, draw) tuples share a number.
#ifndef PHOTON_SHARED_RNG_H
#define PHOTON_SHARED_RNG_H

#include "constants.h"

PH_NAMESPACE_BEGIN

struct Rng {
    uint index;    // pixel or photon path
    uint frame;
    uint key;      // seed ^ stream
    uint counter;  // draws so far
};

PH_FN uvec4 pcg4d(uvec4 v) {
    v = v * 1664525u + uvec4(1013904223u);
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    v = v ^ (v >> 16u);
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    return v;
}

PH_FN Rng rngCreate(uint index, uint frame, uint seed, uint stream) {
    Rng rng;
    rng.index = index;
    rng.frame = frame;
    rng.key = seed ^ stream;
    rng.counter = 0u;
    return rng;
}

PH_FN uint rngNextUint(PH_INOUT(Rng) rng) {
    uvec4 h = pcg4d(uvec4(rng.index, rng.frame, rng.key, rng.counter));
    rng.counter += 1u;
    return h.x;
}

// Uniform in [0, 1): the top 24 bits, exactly representable.
PH_FN float rngNext(PH_INOUT(Rng) rng) {
    return float(rngNextUint(rng) >> 8u) * 5.9604644775390625e-8f;
}

PH_NAMESPACE_END

#endif
