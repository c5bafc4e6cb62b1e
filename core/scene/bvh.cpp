// The host's BVH build: binned SAH (Wald 2007) in four phases; the bins are bvh_bins.h, what the
// phases share bvh_build.h.
//
// 1. Prepare: every primitive's doubled centroid (lo + hi of its box) per axis into three float
//    arrays, and the identity into the index array that the hierarchy partitions. Boxes are not
//    stored: they are computed from the scene where they are needed.
// 2. Top levels (bvh_top_levels.cpp), one level at a time on all threads: a node larger than a
//    subtree bins a regular sample of its primitives along the three axes (over the bounds of the
//    sample's centroids) and chooses its split; the level's nodes are then partitioned in fixed
//    chunks of the index array (each chunk sorts its indices into lefts and rights by their
//    centroid on the split axis alone, then the chunks' pieces are moved to their places), so that
//    even the root's partition is spread over all threads and reads 8 bytes a primitive. Their
//    boxes come last, from their children's.
// 3. Subtrees (bvh_subtrees.cpp): below that size a node is a task of one thread, which copies its
//    primitives' boxes next to each other (32 bytes each; they then stay in its cache) and builds
//    the whole subtree depth first: a node bins its primitives (a regular sample of a large one)
//    along its two longest axes (along the longest alone when it is small or elongated), splits
//    where the SAH cost is lowest, and is partitioned in place (Hoare); its children's boxes are
//    the union of their bins (or, for a sampled node, measured as the partition settles them),
//    their centroids' bounds are measured as it settles them. A node of 5 to 8 primitives becomes
//    two leaves, cut where its sorted centroids give the lowest SAH cost.
// 4. Gather: the top nodes get their boxes; every subtree's nodes are numbered after the earlier
//    subtrees' but stay in the subtree's own array (BinaryBvh), where the collapse to the wide
//    layout (bvh_wide.cpp) reads them: the binary tree is never copied into one array.
//
// The output depends on the scene alone, never on the thread count or on timing: chunks and
// subtrees are cut by size, every chunk's result has its own slot, bins and boxes merge by min and
// max (exact in any order), and every list is kept in the order it was made, not in the order in
// which threads finished.
#include "core/scene/bvh.h"

#include <emmintrin.h>

#include <algorithm>
#include <chrono>

#include "core/scene/bvh_build.h"
#include "core/scene/scene.h"
#include "core/scene/sized_on_helper.h"
#include "core/system/error.h"
#include "core/system/host_memory.h"
#include "core/system/parallel.h"
#include "shared/intersect.h"

namespace photon {
using namespace bvh_build;
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Phase 1: every primitive's doubled centroid and the identity index, in fixed chunks on every
// thread (the arrays' memory is first touched here, by the threads that fill it).
void prepare(Primitives& p, std::size_t total) {
    for (auto& c : p.centroid) {
        c.reset(new float[total]);
        adviseHugePages(c.get(), total * sizeof(float));
    }
    p.index.reset(new std::uint32_t[total]);
    adviseHugePages(p.index.get(), total * sizeof(std::uint32_t));
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
}

}  // namespace

BvhStats buildBinaryBvh(const Scene& scene, BinaryBvh& binary, std::vector<std::uint32_t>& refs) {
    Clock::time_point start = Clock::now();
    binary = BinaryBvh{};
    refs.clear();
    BvhStats stats;
    const std::size_t total = scene.spheres.size() + scene.quads.size() + scene.triangles.size();
    stats.primitives = std::uint32_t(total);
    if (total == 0) {
        stats.buildSeconds = secondsSince(start);
        return stats;
    }
    const RefMap refMap{std::uint32_t(scene.spheres.size()), std::uint32_t(scene.spheres.size() + scene.quads.size())};
    // The references, sized while the centroids are made; the top levels' partitions pass
    // through them before the subtrees write them.
    SizedOnHelper<std::uint32_t> sizedRefs(refs, total, total);

    Primitives p{scene, refMap, {}, {}};
    prepare(p, total);
    stats.prepareSeconds = secondsSince(start);

    Clock::time_point topStart = Clock::now();
    std::vector<TopNode> top;
    std::vector<Subtree> subtrees = buildTopLevels(p, std::uint32_t(total), sizedRefs.get().data(), top);
    stats.topSeconds = secondsSince(topStart);

    // The subtrees, largest first; each into its own nodes.
    Clock::time_point subtreeStart = Clock::now();
    buildSubtrees(p, sizedRefs.get().data(), subtrees);
    stats.subtreeSeconds = secondsSince(subtreeStart);

    // The top nodes, their boxes from their children's (children come after their parents); each
    // subtree's nodes numbered after the earlier subtrees' (they stay where they were built).
    Clock::time_point flattenStart = Clock::now();
    Measure measure;
    binary.offsets.resize(subtrees.size());
    binary.subtrees.resize(subtrees.size());
    auto count = std::uint32_t(top.size());
    for (std::size_t k = 0; k < subtrees.size(); ++k) {
        binary.offsets[k] = count;
        count += std::uint32_t(subtrees[k].nodes.size());
    }
    std::vector<BvhNode>& nodes = binary.top;
    nodes.resize(top.empty() ? 1 : top.size());
    if (top.empty()) {
        // The root is a leaf or a subtree: an inner root with it as its first child and no second.
        const Subtree& s = subtrees[0];
        if (s.nodes.empty()) {
            nodes[0] = emptyNode();
            fill(nodes[0], false, s.box, s.first, s.count, 0, true, measure);
        } else {
            nodes.clear();  // the subtree's root is the root
        }
    } else {
        std::vector<Box> topBoxes(top.size());
        for (std::size_t k = top.size(); k-- > 0;) {
            BvhNode n = emptyNode();
            for (int side = 0; side < 2; ++side) {
                std::uint32_t c = top[k].child[side];
                if (top[k].subtree[side]) {
                    const Subtree& s = subtrees[c];
                    fill(n, side == 1, s.box, s.first, s.count, binary.offsets[c], s.nodes.empty(), measure);
                    topBoxes[k].grow(s.box);
                } else {
                    fill(n, side == 1, topBoxes[c], 0, 0, c, false, measure);
                    topBoxes[k].grow(topBoxes[c]);
                }
            }
            nodes[k] = n;
        }
    }
    for (std::size_t k = 0; k < subtrees.size(); ++k) {
        binary.subtrees[k] = std::move(subtrees[k].nodes);
    }
    // SAH cost: Σ over inner nodes of area/root area times the cost of a visit, plus Σ over leaves
    // of area/root area times their primitives; the root's own visit included.
    std::size_t hint = 0;
    const BvhNode r = binary.node(0, hint);
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
    stats.nodes = count == 0 ? 1 : count;
    stats.flattenSeconds = secondsSince(flattenStart);
    stats.buildSeconds = secondsSince(start);
    return stats;
}

}  // namespace photon
