// The binned SAH's parts (Wald 2007), shared by the build's top levels and subtrees: the build's
// constants, boxes, the map from centroids to bins, the bins, and the split of lowest SAH cost.
#pragma once

#include <emmintrin.h>

#include <algorithm>
#include <cstdint>

#include "core/scene/bvh.h"
#include "shared/intersect.h"

namespace photon::bvh_build {

constexpr int kBins = 8;                        // per axis (tinybvh's BuildAVX: 8)
constexpr std::uint32_t kMaxLeaf = BVH_LEAF_MAX;
constexpr float kTraversalCost = 1.0f;          // of visiting a node, relative to testing a primitive
constexpr std::uint32_t kChunk = 1u << 14;      // primitives per chunk of a top level's partition
constexpr std::uint32_t kTopSamples = 1024;     // a top node bins a regular sample of this many
constexpr std::uint32_t kSampleAbove = 1024;    // a subtree's node larger than this bins a sample
constexpr std::uint32_t kSubtreeSamples = 256;  // of this many
constexpr std::uint32_t kOneAxis = 16;          // nodes up to this size (and elongated ones) bin
                                                // their longest axis only
// Below this depth nodes split at the median along their longest axis instead, so that no input,
// however clustered, makes the hierarchy deeper than the traversal's stack.
constexpr std::uint32_t kMedianDepth = 32;

// Nodes up to this size are subtrees, built whole by one thread: small enough that their boxes
// stay in a core's cache, and at least 64 of them for n primitives, so that every thread has
// work. A function of n alone, so that the tree does not depend on the thread count.
inline std::uint32_t subtreeSize(std::size_t n) {
    return std::uint32_t(std::clamp<std::size_t>(n / 64, 1u << 12, 1u << 15));
}

// A primitive's box; the fourth lanes are 0.
struct alignas(16) PrimBox {
    float lo[4];
    float hi[4];
};

struct Box {
    __m128 lo = _mm_set1_ps(FLOAT_MAX);
    __m128 hi = _mm_set1_ps(-FLOAT_MAX);

    void grow(__m128 l, __m128 h) {
        lo = _mm_min_ps(lo, l);
        hi = _mm_max_ps(hi, h);
    }
    void grow(const Box& b) { grow(b.lo, b.hi); }
    // Half the surface area (the SAH compares, so the factor 2 is left out): dx·dy + dz·dx + dy·dz.
    float area() const {
        __m128 d = _mm_max_ps(_mm_sub_ps(hi, lo), _mm_setzero_ps());  // fourth lane 0 or garbage ≥ 0
        __m128 p = _mm_mul_ps(d, _mm_shuffle_ps(d, d, _MM_SHUFFLE(3, 0, 2, 1)));  // xy, yz, zx, ww
        __m128 s = _mm_add_ss(p, _mm_movehl_ps(p, p));                             // xy + zx
        return _mm_cvtss_f32(_mm_add_ss(s, _mm_shuffle_ps(p, p, _MM_SHUFFLE(1, 1, 1, 1))));
    }
    // The box in the doubled-centroid space (lo + hi) that its primitives' centroids lie in.
    Box doubled() const { return {_mm_add_ps(lo, lo), _mm_add_ps(hi, hi)}; }
    glm::vec3 lower() const { return lane3(lo); }
    glm::vec3 upper() const { return lane3(hi); }
    static glm::vec3 lane3(__m128 v) {
        alignas(16) float f[4];
        _mm_store_ps(f, v);
        return {f[0], f[1], f[2]};
    }
};

// The work of one node: its primitives (a range of the index array), its box, the bounds its
// doubled centroids are binned over, and its depth as an inner node (the root's is 1).
struct Range {
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    Box box;
    Box bounds;
    std::uint32_t depth = 1;
};

// Where a node goes: node `node`'s first (A) or second (B) child.
struct Slot {
    std::uint32_t node = NONE;  // NONE: the root itself
    bool second = false;
};

// How doubled centroids map to B bins over `bounds`: bin = clamp(int((c - offset) · scale), 0,
// B - 1) on each axis. An axis without extent (or with an overflowed one) has scale 0: every
// primitive in bin 0, no split there; NaN goes to bin 0, never through an undefined conversion.
template <int B>
struct BinMap {
    __m128 offset;
    __m128 scale;
    alignas(16) float offsetOf[4];
    alignas(16) float scaleOf[4];

    explicit BinMap(const Box& bounds) {
        alignas(16) float lo[4];
        alignas(16) float hi[4];
        _mm_store_ps(lo, bounds.lo);
        _mm_store_ps(hi, bounds.hi);
        for (int a = 0; a < 3; ++a) {
            float extent = hi[a] - lo[a];
            offsetOf[a] = lo[a];
            scaleOf[a] = extent > 0.0f && extent <= FLOAT_MAX ? float(B) * (1.0f - 1e-6f) / extent : 0.0f;
        }
        offsetOf[3] = 0.0f;
        scaleOf[3] = 0.0f;
        offset = _mm_load_ps(offsetOf);
        scale = _mm_load_ps(scaleOf);
    }

    // Bins along the three axes (lanes 0-2).
    __m128i bins(__m128 lo, __m128 hi) const {
        __m128 t = _mm_mul_ps(_mm_sub_ps(_mm_add_ps(lo, hi), offset), scale);
        t = _mm_min_ps(_mm_max_ps(t, _mm_setzero_ps()), _mm_set1_ps(float(B - 1)));  // max(NaN, 0) = 0
        return _mm_cvttps_epi32(t);
    }

    // The bin along one axis of a doubled centroid, by the same operations as bins() (the same
    // IEEE results: no FMA on x86-64's baseline).
    int bin(float c, int axis) const {
        float t = (c - offsetOf[axis]) * scaleOf[axis];
        return t >= 0.0f ? (t < float(B - 1) ? int(t) : B - 1) : 0;
    }

    // Whether a doubled centroid goes left of a split after `bin` along `axis`: its bin there is
    // at most `bin`, without the conversion (truncation keeps t < bin + 1 below bin + 1).
    bool left(float c, int axis, int bin) const {
        float t = (c - offsetOf[axis]) * scaleOf[axis];
        return !(t >= float(bin + 1));  // NaN: bin 0, left
    }
};

// A bin: the box of its primitives and their number (48 bytes, so that the three axes' bins of a
// primitive are found from one vector of offsets).
struct alignas(16) Bin {
    __m128 lo;
    __m128 hi;
    std::uint32_t count;
    std::uint32_t pad[3];

    void clear() {
        lo = _mm_set1_ps(FLOAT_MAX);
        hi = _mm_set1_ps(-FLOAT_MAX);
        count = 0;
    }
    void add(__m128 l, __m128 h) {
        lo = _mm_min_ps(lo, l);
        hi = _mm_max_ps(hi, h);
        count += 1;
    }
    void merge(const Bin& o) {
        lo = _mm_min_ps(lo, o.lo);
        hi = _mm_max_ps(hi, o.hi);
        count += o.count;
    }
};

// B bins along each axis: axis a's bin b is bin[a * B + b].
template <int B>
struct Bins {
    Bin bin[3 * B];

    // Empties the bins of every axis but `skip` (those are not used).
    explicit Bins(int skip = 3) {
        for (int a = 0; a < 3; ++a) {
            if (a != skip) {
                for (int b = a * B; b < (a + 1) * B; ++b) {
                    bin[b].clear();
                }
            }
        }
    }

    // Adds a primitive to its bins along every axis but `Skip` (3: none).
    template <int Skip = 3>
    void add(const BinMap<B>& map, __m128 lo, __m128 hi) {
        __m128i index = _mm_add_epi32(map.bins(lo, hi), _mm_setr_epi32(0, B, 2 * B, 0));
        __m128i offset = _mm_add_epi32(_mm_slli_epi32(index, 5), _mm_slli_epi32(index, 4));  // × 48 bytes
        auto at = [this](std::uint32_t bytes) { return reinterpret_cast<Bin*>(reinterpret_cast<char*>(bin) + bytes); };
        if (Skip != 0) {
            at(std::uint32_t(_mm_cvtsi128_si32(offset)))->add(lo, hi);
        }
        if (Skip != 1) {
            at(std::uint32_t(_mm_cvtsi128_si32(_mm_shuffle_epi32(offset, 1))))->add(lo, hi);
        }
        if (Skip != 2) {
            at(std::uint32_t(_mm_cvtsi128_si32(_mm_shuffle_epi32(offset, 2))))->add(lo, hi);
        }
    }
    template <int Skip = 3>
    void add(const BinMap<B>& map, const PrimBox& p) {
        add<Skip>(map, _mm_load_ps(p.lo), _mm_load_ps(p.hi));
    }

    void merge(const Bins& o, int skip = 3) {
        for (int a = 0; a < 3; ++a) {
            if (a != skip) {
                for (int b = a * B; b < (a + 1) * B; ++b) {
                    bin[b].merge(o.bin[b]);
                }
            }
        }
    }
    const Bin* axis(int a) const { return bin + a * B; }
};

// A split: left of bin `bin` along `axis` (binned), at the median along `axis`, or none.
struct Split {
    enum Kind { NONE_, BINNED, MEDIAN } kind = NONE_;
    int axis = 0;
    int bin = 0;
};

inline int longestAxis(const Box& b) {
    glm::vec3 extent = b.upper() - b.lower();
    return extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
}

// Whether a node's second longest extent is under half its longest: its split is then all but
// always across the longest (measured: binning the longest alone keeps the SAH cost within 0.3%),
// and binning one axis costs half of binning two.
inline bool elongated(const Box& b) {
    glm::vec3 e = b.upper() - b.lower();
    float longest = std::max(e.x, std::max(e.y, e.z));
    float second = e.x + e.y + e.z - longest - std::min(e.x, std::min(e.y, e.z));
    return second < 0.5f * longest;
}

inline int shortestAxis(const Box& b) {
    glm::vec3 extent = b.upper() - b.lower();
    return extent.x <= extent.y && extent.x <= extent.z ? 0 : (extent.y <= extent.z ? 1 : 2);
}

// The SAH cost of every boundary between one axis' bins, area(left) · n(left) + area(right) ·
// n(right); keeps the lowest in `best` (ties: the earlier axis, then the earlier bin). An empty
// bin changes neither side, so its boundary is not weighed again.
template <int B>
void sweep(const Bin* bins, int axis, Split& best, float& bestCost) {
    float rightArea[B];
    std::uint32_t rightCount[B];
    Box acc;
    std::uint32_t n = 0;
    float accArea = 0.0f;
    for (int b = B - 1; b > 0; --b) {
        if (bins[b].count > 0) {
            acc.grow(bins[b].lo, bins[b].hi);
            n += bins[b].count;
            accArea = acc.area();
        }
        rightArea[b] = accArea;
        rightCount[b] = n;
    }
    acc = Box{};
    n = 0;
    for (int b = 0; b < B - 1; ++b) {
        if (bins[b].count == 0) {
            continue;
        }
        acc.grow(bins[b].lo, bins[b].hi);
        n += bins[b].count;
        if (rightCount[b + 1] == 0) {
            break;
        }
        float cost = acc.area() * float(n) + rightArea[b + 1] * float(rightCount[b + 1]);
        if (cost < bestCost) {
            bestCost = cost;
            best = {Split::BINNED, axis, b};
        }
    }
}

// The split of lowest SAH cost over the bins of every axis, or a median split when no bin
// boundary has primitives on both sides.
template <int B>
Split chooseSplit(const Range& r, const Bins<B>& bins, int skip = 3) {
    Split best;
    float bestCost = FLOAT_MAX;
    for (int a = 0; a < 3; ++a) {
        if (a != skip) {
            sweep<B>(bins.axis(a), a, best, bestCost);
        }
    }
    if (best.kind == Split::NONE_) {
        return {Split::MEDIAN, longestAxis(r.bounds), 0};
    }
    return best;
}

// An absent child: a point beyond every ray's reach (an inverted box would look full to the slab
// test, which sorts its planes).
inline BvhNode emptyNode() {
    BvhNode n{};
    n.lowerA = n.upperA = n.lowerB = n.upperB = glm::vec3(FLOAT_MAX);
    return n;
}

inline bool absent(glm::vec3 lower) { return lower.x == FLOAT_MAX; }

inline double area(glm::vec3 lo, glm::vec3 hi) {
    glm::dvec3 d = glm::max(glm::dvec3(hi) - glm::dvec3(lo), glm::dvec3(0.0));
    return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

}  // namespace photon::bvh_build
