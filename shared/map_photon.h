// The photon maps keep each photon in 16 bytes, half of the photon pass's 32-byte record: the
// seed's compact photon (Jensen's own photon is 20 bytes, "Realistic Image Synthesis Using Photon
// Mapping", 2001, §5.1). The estimates read a cell's photons one after another, so the bytes a
// photon takes are the bytes every query streams through.
//   position  each coordinate relative to the grid's origin, a float rounded to 15 mantissa bits
//             (relative error at most 2^-16: with the hashed grid's origin at the camera, about
//             1/40 of a 1080p pixel's footprint at any distance). It fills a word's high 24 bits,
//             so reading it is a mask.
//   incoming  the octahedral direction at 12 bits an axis (within 0.07°), its three bytes in the low
//             bytes of the position words.
//   power     Ward's RGBE, as Jensen's photon: 8-bit mantissas under one exponent. Mantissas are
//             rounded up with the probability of their fraction (a hash of the photon's identity),
//             so a stored power is the photon's power in expectation. Rounding to nearest would be
//             biased wherever photons share a power: every first bounce of one light off one wall
//             would round the same way, by up to 2% in a dim channel.
// The count step files a photon in the cell of its map position, so the cell that holds a photon
// is the cell of the position the estimates read.
#ifndef PHOTON_SHARED_MAP_PHOTON_H
#define PHOTON_SHARED_MAP_PHOTON_H

#include "layout.h"
#include "rng.h"

PH_NAMESPACE_BEGIN

PH_CONST uint MAP_POSITION_MASK = 0xffffff00u;

// A coordinate relative to `origin`, rounded to its top 24 bits (half up in magnitude: a carry
// into the exponent is the correct rounding too).
PH_FN uint mapCoordinateBits(float x, float origin) {
    return (floatBitsToUint(x - origin) + 0x80u) & MAP_POSITION_MASK;
}

PH_FN vec3 mapPositionFromBits(uint x, uint y, uint z, PH_IN(GridParams) grid) {
    return grid.origin + vec3(uintBitsToFloat(x & MAP_POSITION_MASK), uintBitsToFloat(y & MAP_POSITION_MASK),
                              uintBitsToFloat(z & MAP_POSITION_MASK));
}

// Where the maps keep a photon at `position`.
PH_FN vec3 mapPosition(vec3 position, PH_IN(GridParams) grid) {
    return mapPositionFromBits(mapCoordinateBits(position.x, grid.origin.x), mapCoordinateBits(position.y, grid.origin.y),
                               mapCoordinateBits(position.z, grid.origin.z), grid);
}

// The 16-bit octahedral code (math.h, two snorm16 values 0 .. 65534) to 12 bits an axis and back,
// to the middle of the 16-bit values each 12-bit one stands for.
PH_FN uint octCode24(uint oct32) { return ((oct32 & 0xffffu) >> 4u) | ((oct32 >> 20u) << 12u); }

PH_FN uint octCode32(uint code24) {
    return (((code24 & 0xfffu) << 4u) | 8u) | ((((code24 >> 12u) << 4u) | 8u) << 16u);
}

// Ward's RGBE with stochastic rounding; `u` uniform in [0, 1). The exponent byte X stores
// 2^(X - 127) as the mantissas' scale, so that decoding builds it from bits; X = 0 is no power.
// Powers whose largest channel is below 2^-119 W are stored as none. (Environment texels decode
// at m + 1/2, the middle of the truncated range, environment.h; a photon decodes at m, so that a
// channel of zero stays zero: a photon dispersed to one wavelength, spectral.h.)
PH_FN uint encodePhotonPower(vec3 power, float u) {
    float largest = max(power.x, max(power.y, power.z));
    uint e = (floatBitsToUint(largest) >> 23u) & 0xffu;  // largest ∈ [2^(e - 127), 2^(e - 126))
    if (!(largest > 0.0f) || e < 8u) {
        return 0u;
    }
    e = min(e, 254u);
    // Scale by 2^(134 - e), exactly: the largest mantissa falls in [128, 256). One that would
    // exceed 255 takes the next exponent, so no mantissa rounds past 255.
    vec3 v = power * uintBitsToFloat((261u - e) << 23u);
    if (max(v.x, max(v.y, v.z)) > 255.0f) {
        e += 1u;
        v *= 0.5f;
    }
    vec3 m = clamp(floor(v + vec3(u)), vec3(0.0f), vec3(255.0f));
    return uint(m.x) | (uint(m.y) << 8u) | (uint(m.z) << 16u) | ((e - 7u) << 24u);
}

PH_FN vec3 decodePhotonPower(uint rgbe) {
    vec3 m = vec3(float(rgbe & 0xffu), float((rgbe >> 8u) & 0xffu), float((rgbe >> 16u) & 0xffu));
    return m * uintBitsToFloat((rgbe >> 24u) << 23u);
}

// The map's form of photon `p` of this frame, in the grid of map `grid`.
PH_FN MapPhoton encodeMapPhoton(PH_IN(Photon) p, PH_IN(GridParams) grid, uint frameIndex, uint seed) {
    Rng rng = rngCreate(p.id, frameIndex, seed, STREAM_MAP_PHOTON);
    uint direction = octCode24(p.incoming);
    MapPhoton q;
    q.x = mapCoordinateBits(p.position.x, grid.origin.x) | (direction & 0xffu);
    q.y = mapCoordinateBits(p.position.y, grid.origin.y) | ((direction >> 8u) & 0xffu);
    q.z = mapCoordinateBits(p.position.z, grid.origin.z) | (direction >> 16u);
    q.power = encodePhotonPower(p.power, rngNext(rng));
    return q;
}

// What the estimates read of a map photon, each part apart, so that a query decodes only what it
// needs: most photons it visits lie outside its disc and need no more than their offset.
PH_FN vec3 mapPhotonOffset(PH_IN(MapPhoton) q) {
    return vec3(uintBitsToFloat(q.x & MAP_POSITION_MASK), uintBitsToFloat(q.y & MAP_POSITION_MASK),
                uintBitsToFloat(q.z & MAP_POSITION_MASK));
}

PH_FN vec3 mapPhotonPosition(PH_IN(MapPhoton) q, PH_IN(GridParams) grid) { return mapPositionFromBits(q.x, q.y, q.z, grid); }

PH_FN uint mapPhotonIncoming(PH_IN(MapPhoton) q) {
    return octCode32((q.x & 0xffu) | ((q.y & 0xffu) << 8u) | ((q.z & 0xffu) << 16u));
}

PH_FN vec3 mapPhotonPower(PH_IN(MapPhoton) q) { return decodePhotonPower(q.power); }

// All of a map photon, as a Photon whose id the maps do not keep (0).
PH_FN Photon decodeMapPhoton(PH_IN(MapPhoton) q, PH_IN(GridParams) grid) {
    Photon p;
    p.position = mapPhotonPosition(q, grid);
    p.incoming = mapPhotonIncoming(q);
    p.power = mapPhotonPower(q);
    p.id = 0u;
    return p;
}

PH_NAMESPACE_END

#endif
