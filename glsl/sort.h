// The Vulkan backend's deterministic grid build: a stable least-significant-digit radix sort of
// (cell key, photon id) keys with photon indices as values, 4 bits a pass, after Merrill and
// Grimshaw ("High Performance and Scalable Radix Sorting", 2011) without their decoupled
// look-back: each pass counts every tile's digits (sortCount), scans the counts digit-major
// (sortScan), and moves each tile's elements, in order, to the places the scan gives (sortScatter).
// The host, and the shaders, in the dialect of shared/portable.h.
#ifndef PHOTON_GLSL_SORT_H
#define PHOTON_GLSL_SORT_H

#include "shared/constants.h"

PH_NAMESPACE_BEGIN

PH_CONST uint SORT_DIGIT_BITS = 4u;
PH_CONST uint SORT_BINS = 16u;                     // 2^SORT_DIGIT_BITS
PH_CONST uint SORT_GROUP = 256u;                   // invocations of the per-tile shaders
PH_CONST uint SORT_ITEMS = 8u;                     // elements an invocation moves per tile
PH_CONST uint SORT_TILE = SORT_GROUP * SORT_ITEMS;  // elements of one tile

// Set 1 of the sort shaders (set 0 is the backend's).
PH_CONST uint SORT_BINDING_KEYS = 0u;        // uvec2 (low, high) keys: two arrays of the capacity
PH_CONST uint SORT_BINDING_VALUES = 1u;      // photon indices, likewise
PH_CONST uint SORT_BINDING_HISTOGRAMS = 2u;  // SORT_BINS × tiles counts, digit-major, then scanned
PH_CONST uint SORT_BINDING_STATE = 3u;       // SORT_STATE_* words
PH_CONST uint SORT_BINDING_COUNT = 4u;

// The sort's state: what sortArgs wrote for the map being sorted.
PH_CONST uint SORT_STATE_COUNT = 0u;         // photons to sort
PH_CONST uint SORT_STATE_TILES = 1u;         // tiles of SORT_TILE
PH_CONST uint SORT_STATE_ELEMENT_ARGS = 2u;  // indirect-dispatch groups (x, y, z), GROUP_SIZE per element
PH_CONST uint SORT_STATE_TILE_ARGS = 5u;     // indirect-dispatch groups (x, y, z), one per tile
PH_CONST uint SORT_STATE_WORDS = 8u;

struct SortPush {
    uint map;     // MAP_*
    uint shift;   // the digit of this pass: key bits [shift, shift + 4)
    uint source;  // first element of the pass's input in sortKeys and sortValues
    uint target;  // first element of its output
};

PH_NAMESPACE_END

#ifndef __cplusplus
layout(std430, set = 1, binding = SORT_BINDING_KEYS) restrict buffer SortKeyBuffer { uvec2 sortKeys[]; };
layout(std430, set = 1, binding = SORT_BINDING_VALUES) restrict buffer SortValueBuffer { uint sortValues[]; };
layout(std430, set = 1, binding = SORT_BINDING_HISTOGRAMS) restrict buffer SortHistogramBuffer { uint sortHistograms[]; };
layout(std430, set = 1, binding = SORT_BINDING_STATE) restrict buffer SortStateBuffer { uint sortState[]; };
layout(push_constant) uniform Push { SortPush push; };

// Shifts are multiples of 4, so a digit never straddles the two words.
uint sortDigit(uvec2 key, uint shift) {
    return (shift < 32u ? key.x >> shift : key.y >> (shift - 32u)) & (SORT_BINS - 1u);
}
#endif

#endif
