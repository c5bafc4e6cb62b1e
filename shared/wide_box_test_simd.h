// The CPU's four-box test: a wide node's four child boxes against one ray at once, with SSE2
// (which every x86-64 has), one child in each lane. Only g++ compiling for x86-64 sees the code
// below (it defines PH_WIDE_BOX_SIMD, which traceRay asks); for nvcc, glslang and other CPUs this
// file is empty and they test the children one by one (wideChildEntry). It must give exactly their
// answer: the same entry distance, bit for bit, for every child, so that the children are visited
// in the same order and the images agree.
//
// It does so by doing the same float operations in the same order as intersectBox(wideChildEntry):
// decode a plane (origin + q · scale), distance to it ((plane − ray origin) · inverse direction),
// then the same min/max tree. SSE rounds each operation as the scalar code does, and nothing here
// may be contracted into an FMA (the CPU build has -ffp-contract=off, and no -mfma besides).
#ifndef PHOTON_SHARED_WIDE_BOX_TEST_SIMD_H
#define PHOTON_SHARED_WIDE_BOX_TEST_SIMD_H

#if defined(__cplusplus) && !defined(__CUDACC__) && defined(__SSE2__)
#define PH_WIDE_BOX_SIMD 1

#include <emmintrin.h>

#include "constants.h"
#include "layout.h"

namespace photon {
namespace wide_simd {

// GLM's min(a, b) is (b < a) ? b : a; SSE's minps(x, y) is (x < y) ? x : y. With the operands
// swapped they are the same function, bit for bit, for NaN and ±0 too (either returns its first
// argument when the comparison is false). Likewise GLM's max(a, b) = (a < b) ? b : a = maxps(b, a).
inline __m128 glmMin(__m128 a, __m128 b) { return _mm_min_ps(b, a); }
inline __m128 glmMax(__m128 a, __m128 b) { return _mm_max_ps(b, a); }

// Four words of bytes (16 bytes in memory) as four vectors of four 32-bit lanes: byte i of each
// word in lane i, as (word >> 8i) & 0xff reads it on a little-endian machine.
struct ByteLanes {
    __m128i word0;
    __m128i word1;
    __m128i word2;
    __m128i word3;
};

inline ByteLanes widenBytes(const uint* words) {
    __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(words));
    __m128i zero = _mm_setzero_si128();
    __m128i low = _mm_unpacklo_epi8(bytes, zero);  // words 0 and 1 as 16-bit lanes
    __m128i high = _mm_unpackhi_epi8(bytes, zero); // words 2 and 3
    ByteLanes lanes;
    lanes.word0 = _mm_unpacklo_epi16(low, zero);
    lanes.word1 = _mm_unpackhi_epi16(low, zero);
    lanes.word2 = _mm_unpacklo_epi16(high, zero);
    lanes.word3 = _mm_unpackhi_epi16(high, zero);
    return lanes;
}

// Where the ray crosses the four children's planes q along one axis: (origin + q · scale − ray
// origin) · inverse direction, as intersectBox's t0 and t1.
inline __m128 planeDistances(__m128i q, float origin, float scale, float rayOrigin, float inverseDirection) {
    __m128 plane = _mm_add_ps(_mm_set1_ps(origin), _mm_mul_ps(_mm_cvtepi32_ps(q), _mm_set1_ps(scale)));
    return _mm_mul_ps(_mm_sub_ps(plane, _mm_set1_ps(rayOrigin)), _mm_set1_ps(inverseDirection));
}

// One axis of the slab test for four children: near = min(t0, t1), far = max(t0, t1).
struct Slabs {
    __m128 near;
    __m128 far;
};

inline Slabs slabs(__m128i lower, __m128i upper, float origin, float scale, float rayOrigin, float inverseDirection) {
    __m128 t0 = planeDistances(lower, origin, scale, rayOrigin, inverseDirection);
    __m128 t1 = planeDistances(upper, origin, scale, rayOrigin, inverseDirection);
    Slabs s;
    s.near = glmMin(t0, t1);
    s.far = glmMax(t0, t1);
    return s;
}

// The lanes of the children the node has: those before its first WIDE_CHILD_EMPTY (the portable
// loop stops there), all bits set in a lane that holds one.
inline __m128 presentChildren(__m128i kinds) {
    int empty = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(kinds, _mm_set1_epi32(int(WIDE_CHILD_EMPTY)))));
    int present = __builtin_ctz(unsigned(empty) | 16u);  // the index of the first empty child, or 4
    return _mm_castsi128_ps(_mm_cmplt_epi32(_mm_setr_epi32(0, 1, 2, 3), _mm_set1_epi32(present)));
}

}  // namespace wide_simd

// The entry distances of node n's four children (intersectBox's answer for each, FLOAT_MAX for a
// child missed or absent), as traceRay's portable loop computes them one child at a time.
inline vec4 wideChildEntriesSimd(const WideBvhNode& n, vec3 rayOrigin, vec3 inverseDirection, vec3 scale, float tMax) {
    using namespace wide_simd;
    ByteLanes lower = widenBytes(&n.lowerX);  // lowerX, lowerY, lowerZ, kinds
    ByteLanes upper = widenBytes(&n.upperX);  // upperX, upperY, upperZ, pad0
    Slabs x = slabs(lower.word0, upper.word0, n.origin.x, scale.x, rayOrigin.x, inverseDirection.x);
    Slabs y = slabs(lower.word1, upper.word1, n.origin.y, scale.y, rayOrigin.y, inverseDirection.y);
    Slabs z = slabs(lower.word2, upper.word2, n.origin.z, scale.z, rayOrigin.z, inverseDirection.z);
    __m128 enter = glmMax(glmMax(x.near, y.near), glmMax(z.near, _mm_setzero_ps()));
    __m128 leave = glmMin(glmMin(x.far, y.far), glmMin(z.far, _mm_set1_ps(tMax)));
    __m128 hit = _mm_and_ps(_mm_cmple_ps(enter, leave), presentChildren(lower.word3));
    __m128 entry = _mm_or_ps(_mm_and_ps(hit, enter), _mm_andnot_ps(hit, _mm_set1_ps(FLOAT_MAX)));
    vec4 result;
    _mm_storeu_ps(&result.x, entry);
    return result;
}

}  // namespace photon

#endif  // g++ on x86-64
#endif
