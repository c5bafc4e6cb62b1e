// The host's BVH build: binned SAH (Wald 2007) in four phases.
//
// 1. Prepare: every primitive's doubled centroid (lo + hi of its box) per axis into three float
//    arrays, and the identity into the index array that the hierarchy partitions. Boxes are not
//    stored: they are computed from the scene where they are needed.
// 2. Top levels, one level at a time on all threads: a node larger than a subtree bins a regular
//    sample of its primitives along the three axes (over the bounds of the sample's centroids)
//    and chooses its split; the level's nodes are then partitioned in fixed chunks of the index
//    array (each chunk sorts its indices into lefts and rights by their centroid on the split axis
//    alone, then the chunks' pieces are moved to their places), so that even the root's
//    partition is spread over all threads and reads 8 bytes a primitive. Their boxes come last,
//    from their children's.
// 3. Subtrees: below that size a node is a task of one thread, which copies its primitives' boxes
//    next to each other (32 bytes each; they then stay in its cache) and builds the whole subtree
//    depth first: a node bins its primitives (a regular sample of a large one) along its two
//    longest axes (along the longest alone when it is small or elongated), splits where the SAH
//    cost is lowest, and is partitioned in place (Hoare); its children's boxes are the union of
//    their bins (or, for a sampled node, measured as the partition settles them), their
//    centroids' bounds are measured as it settles them. A node of 5 to 8 primitives becomes two
//    leaves, cut where its sorted centroids give the lowest SAH cost.
// 4. Flatten: the top nodes, then every subtree's nodes in the order the subtrees were made, their
//    child indices offset, into the shared layout.
//
// The output depends on the scene alone, never on the thread count or on timing: chunks and
// subtrees are cut by size, every chunk's result has its own slot, bins and boxes merge by min and
// max (exact in any order), and every list is kept in the order it was made, not in the order in
// which threads finished.
#include "core/scene/bvh.h"

#include <emmintrin.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>

#include "core/scene/scene.h"
#include "core/system/error.h"
#include "core/system/parallel.h"
#include "shared/intersect.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;

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
std::uint32_t subtreeSize(std::size_t n) {
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

int longestAxis(const Box& b) {
    glm::vec3 extent = b.upper() - b.lower();
    return extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
}

// Whether a node's second longest extent is under half its longest: its split is then all but
// always across the longest (measured: binning the longest alone keeps the SAH cost within 0.3%),
// and binning one axis costs half of binning two.
bool elongated(const Box& b) {
    glm::vec3 e = b.upper() - b.lower();
    float longest = std::max(e.x, std::max(e.y, e.z));
    float second = e.x + e.y + e.z - longest - std::min(e.x, std::min(e.y, e.z));
    return second < 0.5f * longest;
}

int shortestAxis(const Box& b) {
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
BvhNode emptyNode() {
    BvhNode n{};
    n.lowerA = n.upperA = n.lowerB = n.upperB = glm::vec3(FLOAT_MAX);
    return n;
}

bool absent(glm::vec3 lower) { return lower.x == FLOAT_MAX; }

double area(glm::vec3 lo, glm::vec3 hi) {
    glm::dvec3 d = glm::max(glm::dvec3(hi) - glm::dvec3(lo), glm::dvec3(0.0));
    return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// What the SAH cost, leaves and depth are summed from, per part of the tree (in an order fixed
// by the tree, so that the sums come out the same every time).
struct Measure {
    double area = 0.0;  // Σ over children: area × (primitives of a leaf, or kTraversalCost)
    std::uint32_t leaves = 0;
    std::uint32_t depth = 0;
};

// Writes a child into its parent's slot: a leaf (references first .. first + count) or inner node
// `index`; counts it in `m`.
void fill(BvhNode& parent, bool second, const Box& box, std::uint32_t first, std::uint32_t count,
          std::uint32_t index, bool leaf, Measure& m) {
    glm::vec3 lo = box.lower();
    glm::vec3 hi = box.upper();
    (second ? parent.lowerB : parent.lowerA) = lo;
    (second ? parent.upperB : parent.upperA) = hi;
    (second ? parent.childB : parent.childA) = leaf ? first : index;
    (second ? parent.countB : parent.countA) = leaf ? count : 0;
    m.area += area(lo, hi) * (leaf ? double(count) : double(kTraversalCost));
    m.leaves += leaf ? 1 : 0;
}

// The primitives' reference (kind << 30 | index) from their place in the box array, which holds
// the spheres, then the quads, then the triangles.
struct RefMap {
    std::uint32_t quads;      // first quad
    std::uint32_t triangles;  // first triangle
    std::uint32_t operator()(std::uint32_t i) const {
        if (i >= triangles) {
            return (PRIM_TRIANGLE << PRIMITIVE_INDEX_BITS) | (i - triangles);
        }
        return i >= quads ? (PRIM_QUAD << PRIMITIVE_INDEX_BITS) | (i - quads) : (PRIM_SPHERE << PRIMITIVE_INDEX_BITS) | i;
    }
};

// What the build works from: the scene's bounded primitives, whose boxes are computed where
// they are needed (never stored: 32 bytes a primitive, written and read once more than they
// save), their doubled centroids per axis, and the index array the hierarchy partitions.
struct Primitives {
    const Scene& scene;
    RefMap refMap;
    std::unique_ptr<float[]> centroid[3];
    std::unique_ptr<std::uint32_t[]> index;

    // The box of primitive i (the spheres, then the quads, then the triangles); fourth lanes 0.
    void box(std::uint32_t i, __m128& lo, __m128& hi) const {
        const __m128 xyz = _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1));
        if (i >= refMap.triangles) {
            const Triangle& t = scene.triangles[i - refMap.triangles];
            __m128 v0 = _mm_load_ps(&t.v0.x);
            __m128 v1 = _mm_load_ps(&t.v1.x);
            __m128 v2 = _mm_load_ps(&t.v2.x);
            lo = _mm_and_ps(_mm_min_ps(v0, _mm_min_ps(v1, v2)), xyz);
            hi = _mm_and_ps(_mm_max_ps(v0, _mm_max_ps(v1, v2)), xyz);
        } else if (i >= refMap.quads) {
            const Quad& q = scene.quads[i - refMap.quads];
            glm::vec3 corners[4] = {q.corner, q.corner + q.edgeU, q.corner + q.edgeV, q.corner + q.edgeU + q.edgeV};
            glm::vec3 l = corners[0];
            glm::vec3 h = corners[0];
            for (glm::vec3 k : corners) {
                l = glm::min(l, k);
                h = glm::max(h, k);
            }
            lo = _mm_setr_ps(l.x, l.y, l.z, 0.0f);
            hi = _mm_setr_ps(h.x, h.y, h.z, 0.0f);
        } else {
            const Sphere& s = scene.spheres[i];
            glm::vec3 l = s.center - glm::vec3(s.radius);
            glm::vec3 h = s.center + glm::vec3(s.radius);
            lo = _mm_setr_ps(l.x, l.y, l.z, 0.0f);
            hi = _mm_setr_ps(h.x, h.y, h.z, 0.0f);
        }
    }
    PrimBox box(std::uint32_t i) const {
        PrimBox b;
        __m128 lo;
        __m128 hi;
        box(i, lo, hi);
        _mm_store_ps(b.lo, lo);
        _mm_store_ps(b.hi, hi);
        return b;
    }
};

// Scratch space of the subtree tasks: one set per task running at once, reused by the next.
struct Scratch {
    std::unique_ptr<PrimBox[]> boxes;
    std::unique_ptr<std::uint32_t[]> ids;
    std::uint32_t capacity = 0;
};

class ScratchPool {
public:
    std::unique_ptr<Scratch> take(std::uint32_t size) {
        std::unique_ptr<Scratch> s;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (!free_.empty()) {
                s = std::move(free_.back());
                free_.pop_back();
            }
        }
        if (!s) {
            s = std::make_unique<Scratch>();
        }
        if (s->capacity < size) {
            s->boxes.reset(new PrimBox[size]);
            s->ids.reset(new std::uint32_t[size]);
            s->capacity = size;
        }
        return s;
    }
    void give(std::unique_ptr<Scratch> s) {
        std::lock_guard<std::mutex> lock(mutex_);
        free_.push_back(std::move(s));
    }

private:
    std::mutex mutex_;
    std::vector<std::unique_ptr<Scratch>> free_;
};

// A subtree: where its root goes, its primitives and box, and its nodes (indexed from 0, moved
// into the whole at the end; none when the root is a leaf).
struct Subtree {
    Slot slot;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    std::uint32_t depth = 1;
    Box box;  // measured by its build
    std::vector<BvhNode> nodes;
    Measure measure;
};

// Builds one subtree on one thread, depth first, over its own copy of its primitives' boxes.
class SubtreeBuilder {
public:
    SubtreeBuilder(const Primitives& p, std::uint32_t* refs, RefMap refMap) : p_(p), refs_(refs), refMap_(refMap) {}

    void build(Subtree& s, Scratch& scratch) const {
        const std::uint32_t first = s.first;
        const std::uint32_t count = s.count;
        PrimBox* boxes = scratch.boxes.get();
        std::uint32_t* ids = scratch.ids.get();
        Box box;
        Box bounds;
        for (std::uint32_t k = 0; k < count; ++k) {
            std::uint32_t id = p_.index[first + k];
            ids[k] = id;
            __m128 lo;
            __m128 hi;
            p_.box(id, lo, hi);
            _mm_store_ps(boxes[k].lo, lo);
            _mm_store_ps(boxes[k].hi, hi);
            box.grow(lo, hi);
            __m128 c = _mm_add_ps(lo, hi);
            bounds.grow(c, c);
        }
        s.box = box;
        Measure& m = s.measure;
        if (count > kMaxLeaf) {
            // Ranges are local (0 .. count) while building; leaves are written with global firsts.
            struct Pending {
                Slot slot;
                Range range;
            };
            // Depth first, the right child waits: at most one pending range per level, and there
            // are fewer than kMedianDepth + 32 levels below a subtree's root.
            constexpr int kStack = 2 * kMedianDepth + 64;
            Pending stack[kStack];
            int top = 0;
            s.nodes.reserve(count / 2 + 1);
            stack[top++] = {Slot{NONE, false}, Range{0, count, box, bounds, s.depth}};
            while (top > 0) {
                Pending p = stack[--top];
                if (p.range.count <= kMaxLeaf) {
                    fill(s.nodes[p.slot.node], p.slot.second, p.range.box, p.range.first + first, p.range.count, 0,
                         true, m);
                    continue;
                }
                auto index = std::uint32_t(s.nodes.size());
                if (p.slot.node != NONE) {
                    fill(s.nodes[p.slot.node], p.slot.second, p.range.box, 0, 0, index, false, m);
                }
                s.nodes.push_back(emptyNode());
                m.depth = std::max(m.depth, p.range.depth);
                if (p.range.count <= 2 * kMaxLeaf) {
                    // Two leaves, by the exact SAH cost along the longest axis.
                    const std::uint32_t at = p.range.first;
                    Box lb;
                    Box rb;
                    std::uint32_t k = splitSmall(boxes + at, ids + at, p.range.count, longestAxis(p.range.bounds), lb, rb);
                    fill(s.nodes[index], false, lb, first + at, k, 0, true, m);
                    fill(s.nodes[index], true, rb, first + at + k, p.range.count - k, 0, true, m);
                    continue;
                }
                Range left;
                Range right;
                split(boxes, ids, p.range, left, right, s.slot.node != NONE);
                stack[top++] = {Slot{index, true}, right};
                stack[top++] = {Slot{index, false}, left};
                if (top > kStack - 2) {
                    throw InputError("the scene's bounding volume hierarchy is too deep to build");
                }
            }
        }
        for (std::uint32_t k = 0; k < count; ++k) {
            refs_[first + k] = refMap_(ids[k]);
        }
    }

private:
    static float centroid(const PrimBox& p, int axis) { return p.lo[axis] + p.hi[axis]; }

    // Splits n = kMaxLeaf + 1 .. 2 kMaxLeaf primitives into two leaves, in place: sorted by
    // centroid along `axis` (ties keep their order), cut where area(left) · n(left) +
    // area(right) · n(right) is lowest among the cuts that leave at most kMaxLeaf on a side.
    // Returns the left side's count.
    static std::uint32_t splitSmall(PrimBox* boxes, std::uint32_t* ids, std::uint32_t n, int axis, Box& left,
                                    Box& right) {
        constexpr std::uint32_t kMax = 2 * kMaxLeaf;
        float key[kMax];
        std::uint32_t order[kMax];
        for (std::uint32_t i = 0; i < n; ++i) {
            key[i] = centroid(boxes[i], axis);
            order[i] = i;
            for (std::uint32_t j = i; j > 0 && key[order[j - 1]] > key[i]; --j) {
                std::swap(order[j - 1], order[j]);
            }
        }
        PrimBox sorted[kMax];
        std::uint32_t sortedIds[kMax];
        for (std::uint32_t i = 0; i < n; ++i) {
            sorted[i] = boxes[order[i]];
            sortedIds[i] = ids[order[i]];
        }
        Box prefix[kMax];
        Box suffix[kMax];
        Box acc;
        for (std::uint32_t i = 0; i + 1 < n; ++i) {
            acc.grow(_mm_load_ps(sorted[i].lo), _mm_load_ps(sorted[i].hi));
            prefix[i + 1] = acc;
        }
        acc = Box{};
        for (std::uint32_t i = n - 1; i > 0; --i) {
            acc.grow(_mm_load_ps(sorted[i].lo), _mm_load_ps(sorted[i].hi));
            suffix[i] = acc;
        }
        float bestCost = FLOAT_MAX;
        std::uint32_t best = kMaxLeaf;  // always allowed
        for (std::uint32_t k = n - kMaxLeaf; k <= kMaxLeaf; ++k) {
            float cost = prefix[k].area() * float(k) + suffix[k].area() * float(n - k);
            if (cost < bestCost) {
                bestCost = cost;
                best = k;
            }
        }
        std::copy(sorted, sorted + n, boxes);
        std::copy(sortedIds, sortedIds + n, ids);
        left = prefix[best];
        right = suffix[best];
        return best;
    }

    // Splits a range of more than 2 kMaxLeaf primitives and measures both sides; `sample`: large
    // nodes may bin a sample.
    static void split(PrimBox* boxes, std::uint32_t* ids, const Range& r, Range& left, Range& right, bool sample) {
        left = Range{r.first, 0, {}, {}, r.depth + 1};
        right = Range{0, 0, {}, {}, r.depth + 1};
        if (r.depth >= kMedianDepth) {
            splitAtMedian(boxes, ids, r, longestAxis(r.bounds), left, right);
            return;
        }
        const std::uint32_t end = r.first + r.count;
        BinMap<kBins> map(r.bounds);
        if (r.count <= kOneAxis || elongated(r.bounds)) {
            // Small: the longest axis only.
            int axis = longestAxis(r.bounds);
            Bin bins[kBins];
            for (Bin& b : bins) {
                b.clear();
            }
            for (std::uint32_t i = r.first; i < end; ++i) {
                bins[map.bin(centroid(boxes[i], axis), axis)].add(_mm_load_ps(boxes[i].lo), _mm_load_ps(boxes[i].hi));
            }
            Split s;
            float cost = FLOAT_MAX;
            sweep<kBins>(bins, axis, s, cost);
            if (s.kind == Split::NONE_) {
                splitAtMedian(boxes, ids, r, axis, left, right);
                return;
            }
            partition<false>(boxes, ids, r, s, map, left, right);
            measureFromBins(bins, s, left, right);
            return;
        }
        // The shortest axis is left out: splits across it are almost never the best (measured:
        // the SAH cost of the trees is the same), and binning it costs a third of the binning.
        // Below the top levels a large node bins a regular sample (measured: the SAH cost within
        // 0.1%, the subtrees 10% faster); the root subtree of a scene too small for top levels
        // bins every primitive (a sample there misses the few large ones, such as walls, that
        // decide the cost of the scene's top nodes).
        const int skip = shortestAxis(r.bounds);
        Bins<kBins> bins(skip);
        const bool sampled = sample && r.count > kSampleAbove;
        const std::uint32_t stride = sampled ? r.count / kSubtreeSamples : 1;
        switch (skip) {
            case 0: binRange<0>(bins, map, boxes, r.first, end, stride); break;
            case 1: binRange<1>(bins, map, boxes, r.first, end, stride); break;
            default: binRange<2>(bins, map, boxes, r.first, end, stride); break;
        }
        Split s = chooseSplit(r, bins, skip);
        if (s.kind == Split::MEDIAN) {
            splitAtMedian(boxes, ids, r, s.axis, left, right);
            return;
        }
        if (sampled) {
            partition<true>(boxes, ids, r, s, map, left, right);
            if (left.count == 0 || right.count == 0) {
                left = Range{r.first, 0, {}, {}, r.depth + 1};
                right = Range{0, 0, {}, {}, r.depth + 1};
                splitAtMedian(boxes, ids, r, longestAxis(r.bounds), left, right);
            }
            return;
        }
        partition<false>(boxes, ids, r, s, map, left, right);
        measureFromBins(bins.axis(s.axis), s, left, right);
    }

    template <int Skip>
    static void binRange(Bins<kBins>& bins, const BinMap<kBins>& map, const PrimBox* boxes, std::uint32_t first,
                         std::uint32_t end, std::uint32_t stride) {
        for (std::uint32_t i = first; i < end; i += stride) {
            bins.add<Skip>(map, boxes[i]);
        }
    }

    // Every primitive was binned: each side's box is the union of its bins.
    static void measureFromBins(const Bin* bins, const Split& s, Range& left, Range& right) {
        for (int b = 0; b < kBins; ++b) {
            (b <= s.bin ? left : right).box.grow(bins[b].lo, bins[b].hi);
        }
    }

    // Hoare's partition by a binned split, lefts first, measuring each side's centroid bounds as
    // its primitives settle, and their boxes too when `Boxes` (a sampled node's bins do not hold
    // every primitive).
    template <bool Boxes>
    static void partition(PrimBox* boxes, std::uint32_t* ids, const Range& r, const Split& s, const BinMap<kBins>& map,
                          Range& left, Range& right) {
        const int axis = s.axis;
        const int bin = s.bin;
        std::uint32_t i = r.first;
        std::uint32_t j = r.first + r.count;  // one past the last unsettled primitive
        Box lb;
        Box lc;
        Box rb;
        Box rc;
        auto settle = [&](std::uint32_t k, Box& box, Box& centroids) {
            __m128 lo = _mm_load_ps(boxes[k].lo);
            __m128 hi = _mm_load_ps(boxes[k].hi);
            if (Boxes) {
                box.grow(lo, hi);
            }
            __m128 c = _mm_add_ps(lo, hi);
            centroids.grow(c, c);
        };
        while (true) {
            while (i < j && map.left(centroid(boxes[i], axis), axis, bin)) {
                settle(i, lb, lc);
                ++i;
            }
            while (i < j && !map.left(centroid(boxes[j - 1], axis), axis, bin)) {
                settle(j - 1, rb, rc);
                --j;
            }
            if (i >= j) {
                break;
            }
            std::swap(boxes[i], boxes[j - 1]);
            std::swap(ids[i], ids[j - 1]);
            settle(i, lb, lc);
            settle(j - 1, rb, rc);
            ++i;
            --j;
        }
        left.count = i - r.first;
        left.bounds = lc;
        right.first = i;
        right.count = r.first + r.count - i;
        right.bounds = rc;
        if (Boxes) {
            left.box = lb;
            right.box = rb;
        }
    }

    // Half the primitives on each side, split at the median of their centroids along `axis`.
    static void splitAtMedian(PrimBox* boxes, std::uint32_t* ids, const Range& r, int axis, Range& left, Range& right) {
        std::vector<std::pair<float, std::uint32_t>> keys(r.count);
        for (std::uint32_t k = 0; k < r.count; ++k) {
            keys[k] = {centroid(boxes[r.first + k], axis), k};
        }
        std::nth_element(keys.begin(), keys.begin() + r.count / 2, keys.end());
        std::vector<PrimBox> b(r.count);
        std::vector<std::uint32_t> d(r.count);
        for (std::uint32_t k = 0; k < r.count; ++k) {
            b[k] = boxes[r.first + keys[k].second];
            d[k] = ids[r.first + keys[k].second];
        }
        std::copy(b.begin(), b.end(), boxes + r.first);
        std::copy(d.begin(), d.end(), ids + r.first);
        left.count = r.count / 2;
        right.first = r.first + r.count / 2;
        right.count = r.count - r.count / 2;
        for (Range* side : {&left, &right}) {
            for (std::uint32_t i = side->first; i < side->first + side->count; ++i) {
                side->box.grow(_mm_load_ps(boxes[i].lo), _mm_load_ps(boxes[i].hi));
            }
            side->bounds = side->box.doubled();
        }
    }

    const Primitives& p_;
    std::uint32_t* refs_;
    RefMap refMap_;
};

// A node of the top levels: where it goes and what its children are (a top node or a subtree).
struct TopNode {
    std::uint32_t child[2];
    bool subtree[2];
};

// The top levels: nodes larger than a subtree, a level at a time, each spread over every thread.
class TopLevels {
public:
    TopLevels(const Primitives& p, std::uint32_t* scratch, std::uint32_t subtreeSize)
        : p_(p), scratch_(scratch), subtreeSize_(subtreeSize) {}

    // Splits from the root down until every node is a subtree's size; returns the subtrees in the
    // order they were made. Top node k is node k of the hierarchy.
    std::vector<Subtree> run(std::uint32_t count, std::vector<TopNode>& nodes) {
        std::vector<Subtree> subtrees;
        if (count <= subtreeSize_) {
            Subtree s;
            s.count = count;
            subtrees.push_back(std::move(s));
            return subtrees;
        }
        std::vector<Open> open;
        open.push_back({Slot{}, 0, count, 1, 0, {}, {}});
        while (!open.empty()) {
            // Each open node becomes a top node, in order, and chooses its split from a sample.
            for (Open& o : open) {
                o.node = std::uint32_t(nodes.size());
                nodes.push_back({});
                if (o.slot.node != NONE) {
                    nodes[o.slot.node].child[o.slot.second] = o.node;
                    nodes[o.slot.node].subtree[o.slot.second] = false;
                }
            }
            parallelFor(open.size(), 1, [&](std::size_t a, std::size_t b) {
                for (std::size_t k = a; k < b; ++k) {
                    chooseSampled(open[k]);
                }
            });
            // The chunks of every binned node, in order.
            std::vector<Chunk> chunks;
            std::vector<std::uint32_t> firstChunk(open.size() + 1);
            for (std::uint32_t k = 0; k < open.size(); ++k) {
                firstChunk[k] = std::uint32_t(chunks.size());
                const Open& o = open[k];
                if (o.split.kind != Split::BINNED) {
                    continue;
                }
                for (std::uint32_t c = 0; c < o.count; c += kChunk) {
                    chunks.push_back({k, o.first + c, std::min(kChunk, o.count - c), 0, 0, 0});
                }
            }
            firstChunk[open.size()] = std::uint32_t(chunks.size());
            parallelFor(chunks.size(), 1, [&](std::size_t a, std::size_t b) {
                for (std::size_t c = a; c < b; ++c) {
                    partitionChunk(open[chunks[c].open], chunks[c]);
                }
            });
            // Each chunk's lefts and rights go after the earlier chunks' of the same node.
            std::vector<std::uint32_t> lefts(open.size(), 0);
            for (std::uint32_t k = 0; k < open.size(); ++k) {
                std::uint32_t at = open[k].first;
                for (std::uint32_t c = firstChunk[k]; c < firstChunk[k + 1]; ++c) {
                    chunks[c].leftAt = at;
                    at += chunks[c].lefts;
                }
                lefts[k] = at - open[k].first;
                for (std::uint32_t c = firstChunk[k]; c < firstChunk[k + 1]; ++c) {
                    chunks[c].rightAt = at;
                    at += chunks[c].count - chunks[c].lefts;
                }
            }
            parallelFor(chunks.size(), 1, [&](std::size_t a, std::size_t b) {
                for (std::size_t c = a; c < b; ++c) {
                    const Chunk& chunk = chunks[c];
                    std::uint32_t* index = p_.index.get();
                    std::copy(scratch_ + chunk.first, scratch_ + chunk.first + chunk.lefts, index + chunk.leftAt);
                    std::reverse_copy(scratch_ + chunk.first + chunk.lefts, scratch_ + chunk.first + chunk.count,
                                      index + chunk.rightAt);
                }
            });
            // Median splits (a sample without a split, a split that parts nothing, or too deep):
            // rare, one node at a time.
            for (std::uint32_t k = 0; k < open.size(); ++k) {
                const Open& o = open[k];
                if (o.split.kind != Split::BINNED || lefts[k] == 0 || lefts[k] == o.count) {
                    splitAtMedian(o, o.split.kind == Split::BINNED ? longestAxis(o.bounds) : o.split.axis);
                    lefts[k] = o.count / 2;
                }
            }
            // The children: open again if still large, else subtrees.
            std::vector<Open> next;
            for (std::uint32_t k = 0; k < open.size(); ++k) {
                const Open& o = open[k];
                for (int side = 0; side < 2; ++side) {
                    std::uint32_t first = side ? o.first + lefts[k] : o.first;
                    std::uint32_t n = side ? o.count - lefts[k] : lefts[k];
                    Slot slot{o.node, side == 1};
                    if (n > subtreeSize_) {
                        next.push_back({slot, first, n, o.depth + 1, 0, {}, {}});
                    } else {
                        nodes[o.node].child[side] = std::uint32_t(subtrees.size());
                        nodes[o.node].subtree[side] = true;
                        Subtree s;
                        s.slot = slot;
                        s.first = first;
                        s.count = n;
                        s.depth = o.depth + 1;
                        subtrees.push_back(std::move(s));
                    }
                }
            }
            open = std::move(next);
        }
        return subtrees;
    }

private:
    struct Open {
        Slot slot;
        std::uint32_t first;
        std::uint32_t count;
        std::uint32_t depth;
        std::uint32_t node;  // its index among the nodes
        Box bounds;          // of its sample's doubled centroids
        Split split;
    };

    // A piece of a node's partition: its lefts go to scratch first .. first + lefts in order, its
    // rights from the piece's end down.
    struct alignas(64) Chunk {
        std::uint32_t open;
        std::uint32_t first;
        std::uint32_t count;
        std::uint32_t lefts;
        std::uint32_t leftAt;   // where its lefts go in the index array
        std::uint32_t rightAt;  // and its rights
    };

    void chooseSampled(Open& o) const {
        const std::uint32_t samples = kTopSamples;
        const std::uint32_t stride = std::max(1u, o.count / samples);
        const std::uint32_t* index = p_.index.get();
        for (std::uint32_t i = o.first; i < o.first + o.count; i += stride) {
            std::uint32_t id = index[i];
            __m128 c = _mm_setr_ps(p_.centroid[0][id], p_.centroid[1][id], p_.centroid[2][id], 0.0f);
            o.bounds.grow(c, c);
        }
        Range r{o.first, o.count, {}, o.bounds, o.depth};
        if (o.depth >= kMedianDepth) {
            o.split = {Split::MEDIAN, longestAxis(o.bounds), 0};
            return;
        }
        BinMap<kBins> map(o.bounds);
        Bins<kBins> bins;
        for (std::uint32_t i = o.first; i < o.first + o.count; i += stride) {
            bins.add(map, p_.box(index[i]));
        }
        o.split = chooseSplit(r, bins);
    }

    void partitionChunk(const Open& o, Chunk& chunk) const {
        const BinMap<kBins> map(o.bounds);
        const int axis = o.split.axis;
        const float offset = map.offsetOf[axis];
        const float scale = map.scaleOf[axis];
        const float limit = float(o.split.bin + 1);
        const float* c = p_.centroid[axis].get();
        const std::uint32_t* index = p_.index.get();
        const std::uint32_t* in = index + chunk.first;
        std::uint32_t* lefts = scratch_ + chunk.first;
        std::uint32_t* rights = scratch_ + chunk.first + chunk.count - 1;  // written downwards
        std::uint32_t nl = 0;
        // Without branches: every index is written to both sides' next places, and one of them
        // advances (the same test as BinMap::left); k - nl rights so far.
        for (std::uint32_t k = 0; k < chunk.count; ++k) {
            std::uint32_t id = in[k];
            std::uint32_t right = (c[id] - offset) * scale >= limit;
            lefts[nl] = id;
            rights[std::ptrdiff_t(nl) - std::ptrdiff_t(k)] = id;
            nl += 1 - right;
        }
        chunk.lefts = nl;
    }

    void splitAtMedian(const Open& o, int axis) const {
        std::uint32_t* begin = p_.index.get() + o.first;
        const float* c = p_.centroid[axis].get();
        std::nth_element(begin, begin + o.count / 2, begin + o.count, [&](std::uint32_t a, std::uint32_t b) {
            return c[a] < c[b] || (c[a] == c[b] && a < b);
        });
    }

    const Primitives& p_;
    std::uint32_t* scratch_;
    std::uint32_t subtreeSize_;
};

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The output arrays, sized on a helper thread while the build runs: a vector's resize zeroes its
// memory on one thread, and the first touch of fresh memory is a page fault per 4 KiB (at 10M
// triangles 0.06 s for the nodes alone, a tenth of the build, on a 2-core machine). The
// references are ready for the subtrees, the nodes (as many as a tree of these primitives
// usually has, 0.3 a primitive; the flatten sizes them exactly) for the flatten.
class Outputs {
public:
    Outputs(std::vector<BvhNode>& nodes, std::vector<std::uint32_t>& refs, std::size_t primitives)
        : nodes_(nodes), refs_(refs) {
        nodes.reserve(primitives / 2 + 64);  // more than a tree of leaves of 4 or fewer ever needs
        std::size_t estimate = primitives * 3 / 10;
        auto work = [this, primitives, estimate] {
            try {
                refs_.resize(primitives);
            } catch (...) {
                refsFailure_ = std::current_exception();
            }
            {
                std::lock_guard<std::mutex> lock(mutex_);
                refsReady_ = true;
            }
            ready_.notify_all();
            try {
                nodes_.resize(std::min(estimate, nodes_.capacity()));
            } catch (...) {
                nodesFailure_ = std::current_exception();
            }
        };
        try {
            helper_ = std::thread(work);
        } catch (const std::system_error&) {
            work();  // no thread to spare: here and now
        }
    }
    ~Outputs() {
        if (helper_.joinable()) {
            helper_.join();
        }
    }
    Outputs(const Outputs&) = delete;
    Outputs& operator=(const Outputs&) = delete;

    std::uint32_t* refs() {
        std::unique_lock<std::mutex> lock(mutex_);
        ready_.wait(lock, [this] { return refsReady_; });
        if (refsFailure_) {
            std::rethrow_exception(refsFailure_);
        }
        return refs_.data();
    }
    std::vector<BvhNode>& nodes() {
        if (helper_.joinable()) {
            helper_.join();
        }
        if (nodesFailure_) {
            std::rethrow_exception(nodesFailure_);
        }
        return nodes_;
    }

private:
    std::vector<BvhNode>& nodes_;
    std::vector<std::uint32_t>& refs_;
    std::thread helper_;
    std::mutex mutex_;
    std::condition_variable ready_;
    bool refsReady_ = false;
    std::exception_ptr refsFailure_;
    std::exception_ptr nodesFailure_;
};

}  // namespace

BvhStats buildBinaryBvh(const Scene& scene, std::vector<BvhNode>& nodes, std::vector<std::uint32_t>& refs) {
    Clock::time_point start = Clock::now();
    nodes.clear();
    refs.clear();
    BvhStats stats;
    const std::size_t total = scene.spheres.size() + scene.quads.size() + scene.triangles.size();
    stats.primitives = std::uint32_t(total);
    if (total == 0) {
        stats.buildSeconds = secondsSince(start);
        return stats;
    }
    const RefMap refMap{std::uint32_t(scene.spheres.size()), std::uint32_t(scene.spheres.size() + scene.quads.size())};
    Outputs outputs(nodes, refs, total);

    // Every primitive's doubled centroid and the identity index, in fixed chunks on every thread
    // (the arrays' memory is first touched here, by the threads that fill it).
    Primitives p{scene, refMap, {}, {}};
    for (auto& c : p.centroid) {
        c.reset(new float[total]);
    }
    p.index.reset(new std::uint32_t[total]);
    constexpr std::size_t kPrepareChunk = 1u << 16;
    parallelFor((total + kPrepareChunk - 1) / kPrepareChunk, 1, [&](std::size_t a, std::size_t b) {
        for (auto i = std::uint32_t(a * kPrepareChunk); i < std::min(total, b * kPrepareChunk); ++i) {
            __m128 lo;
            __m128 hi;
            p.box(i, lo, hi);
            alignas(16) float c[4];
            _mm_store_ps(c, _mm_add_ps(lo, hi));
            p.centroid[0][i] = c[0];
            p.centroid[1][i] = c[1];
            p.centroid[2][i] = c[2];
            p.index[i] = i;
        }
    });
    stats.prepareSeconds = secondsSince(start);

    Clock::time_point topStart = Clock::now();
    std::vector<TopNode> top;
    std::vector<Subtree> subtrees;
    {
        std::unique_ptr<std::uint32_t[]> scratch(new std::uint32_t[total]);  // of the partitions
        subtrees = TopLevels(p, scratch.get(), subtreeSize(total)).run(std::uint32_t(total), top);
    }
    stats.topSeconds = secondsSince(topStart);

    // The subtrees, largest first (so that the last to start are short); each into its own nodes.
    Clock::time_point subtreeStart = Clock::now();
    std::vector<std::uint32_t> order(subtrees.size());
    for (std::uint32_t k = 0; k < order.size(); ++k) {
        order[k] = k;
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return subtrees[a].count > subtrees[b].count; });
    ScratchPool scratch;
    SubtreeBuilder builder(p, outputs.refs(), refMap);
    parallelFor(order.size(), 1, [&](std::size_t a, std::size_t b) {
        for (std::size_t k = a; k < b; ++k) {
            Subtree& s = subtrees[order[k]];
            std::unique_ptr<Scratch> space = scratch.take(s.count);
            builder.build(s, *space);
            scratch.give(std::move(space));
        }
    });
    stats.subtreeSeconds = secondsSince(subtreeStart);

    // The top nodes first, their boxes from their children's (children come after their
    // parents), then each subtree's nodes after the earlier subtrees'.
    Clock::time_point flattenStart = Clock::now();
    Measure measure;
    std::vector<std::uint32_t> offsets(subtrees.size());
    auto count = std::uint32_t(top.size());
    for (std::size_t k = 0; k < subtrees.size(); ++k) {
        offsets[k] = count;
        count += std::uint32_t(subtrees[k].nodes.size());
    }
    outputs.nodes().resize(count == 0 ? 1 : count);
    if (count == 0) {
        // The root is a leaf: an inner root with it as its first child and no second.
        nodes[0] = emptyNode();
        fill(nodes[0], false, subtrees[0].box, 0, subtrees[0].count, 0, true, measure);
    } else {
        std::vector<Box> topBoxes(top.size());
        for (std::size_t k = top.size(); k-- > 0;) {
            BvhNode n = emptyNode();
            for (int side = 0; side < 2; ++side) {
                std::uint32_t c = top[k].child[side];
                if (top[k].subtree[side]) {
                    const Subtree& s = subtrees[c];
                    fill(n, side == 1, s.box, s.first, s.count, offsets[c], s.nodes.empty(), measure);
                    topBoxes[k].grow(s.box);
                } else {
                    fill(n, side == 1, topBoxes[c], 0, 0, c, false, measure);
                    topBoxes[k].grow(topBoxes[c]);
                }
            }
            nodes[k] = n;
        }
        parallelFor(subtrees.size(), 1, [&](std::size_t a, std::size_t b) {
            for (std::size_t k = a; k < b; ++k) {
                const std::uint32_t offset = offsets[k];
                BvhNode* out = nodes.data() + offset;
                for (BvhNode n : subtrees[k].nodes) {
                    n.childA += n.countA == 0 && !absent(n.lowerA) ? offset : 0;
                    n.childB += n.countB == 0 && !absent(n.lowerB) ? offset : 0;
                    *out++ = n;
                }
            }
        });
    }
    // SAH cost: Σ over inner nodes of area/root area times the cost of a visit, plus Σ over leaves
    // of area/root area times their primitives; the root's own visit included.
    const BvhNode& r = nodes[0];
    glm::vec3 lo = absent(r.lowerB) ? r.lowerA : glm::min(r.lowerA, r.lowerB);
    glm::vec3 hi = absent(r.lowerB) ? r.upperA : glm::max(r.upperA, r.upperB);
    double rootArea = std::max(area(lo, hi), 1e-30);
    double sum = measure.area;
    stats.leaves = measure.leaves;
    stats.depth = 1;
    // The top levels' depth: the deepest top node (they are made a level at a time).
    for (const Subtree& s : subtrees) {
        stats.depth = std::max(stats.depth, s.depth - 1);
    }
    for (const Subtree& s : subtrees) {
        sum += s.measure.area;
        stats.leaves += s.measure.leaves;
        stats.depth = std::max(stats.depth, s.measure.depth);
    }
    stats.sahCost = kTraversalCost + sum / rootArea;
    stats.nodes = std::uint32_t(nodes.size());
    stats.flattenSeconds = secondsSince(flattenStart);
    stats.buildSeconds = secondsSince(start);
    return stats;
}

}  // namespace photon
