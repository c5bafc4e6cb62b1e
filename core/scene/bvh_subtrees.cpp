// Phase 3 of the BVH build (core/scene/bvh.cpp): the subtrees below the top levels, each built
// whole, depth first, by one thread over its own copy of its primitives' boxes.
#include <mutex>

#include "core/scene/bvh_build.h"
#include "core/system/error.h"
#include "core/system/host_memory.h"
#include "core/system/parallel.h"

namespace photon::bvh_build {
namespace {

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
            adviseHugePages(s->boxes.get(), size * sizeof(PrimBox));
            adviseHugePages(s->ids.get(), size * sizeof(std::uint32_t));
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
            adviseHugePages(s.nodes.data(), s.nodes.capacity() * sizeof(BvhNode));
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

}  // namespace

void buildSubtrees(const Primitives& p, std::uint32_t* refs, std::vector<Subtree>& subtrees) {
    // The subtrees, largest first (so that the last to start are short); each into its own nodes.
    std::vector<std::uint32_t> order(subtrees.size());
    for (std::uint32_t k = 0; k < order.size(); ++k) {
        order[k] = k;
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return subtrees[a].count > subtrees[b].count; });
    ScratchPool scratch;
    SubtreeBuilder builder(p, refs, p.refMap);
    parallelFor(order.size(), 1, [&](std::size_t a, std::size_t b) {
        for (std::size_t k = a; k < b; ++k) {
            Subtree& s = subtrees[order[k]];
            std::unique_ptr<Scratch> space = scratch.take(s.count);
            builder.build(s, *space);
            scratch.give(std::move(space));
        }
    });
}

}  // namespace photon::bvh_build
