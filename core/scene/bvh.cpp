// The host's BVH build: binned SAH (Wald 2007) in four phases, the last two of which also collapse
// the binary tree into the wide layout (bvh_wide.cpp); the bins are bvh_bins.h, what the phases
// share bvh_build.h.
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
//    two leaves, cut where its sorted centroids give the lowest SAH cost. The same thread then
//    collapses the subtree's binary nodes, still in its cache, into the subtree's own wide nodes;
//    the binary nodes' memory is the thread's scratch, reused by its next subtree, so the binary
//    tree is never kept whole.
// 4. Top: the top nodes get their boxes and the binary tree is measured; the top nodes are
//    collapsed into wide nodes (each subtree's root a wide node of its own) and every subtree's
//    wide nodes are placed after them.
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

BvhStats buildBvh(const Scene& scene, std::vector<WideBvhNode>& wide, std::vector<std::uint32_t>& refs) {
    Clock::time_point start = Clock::now();
    refs.clear();
    BvhStats stats;
    const std::size_t total = scene.spheres.size() + scene.quads.size() + scene.triangles.size();
    stats.primitives = std::uint32_t(total);
    if (total == 0) {
        wide.clear();
        stats.buildSeconds = secondsSince(start);
        return stats;
    }
    const RefMap refMap{std::uint32_t(scene.spheres.size()), std::uint32_t(scene.spheres.size() + scene.quads.size())};
    // The references, sized while the centroids are made; the top levels' partitions pass
    // through them before the subtrees write them.
    SizedOnHelper<std::uint32_t> sizedRefs(refs, total, total);
    // The wide nodes, sized while the tree is built: the bench's meshes have a wide node per 6.8
    // primitives, the estimate is a little more (widenTop sizes them exactly). Address space is
    // reserved for half a node a primitive (untouched pages cost nothing), so that a tree larger
    // than the estimate is not moved.
    SizedOnHelper<WideBvhNode> sizedWide(wide, total / 2 + 64, total * 3 / 20);

    Primitives p{scene, refMap, {}, {}};
    prepare(p, total);
    stats.prepareSeconds = secondsSince(start);

    Clock::time_point topStart = Clock::now();
    std::vector<TopNode> top;
    std::vector<Subtree> subtrees = buildTopLevels(p, std::uint32_t(total), sizedRefs.get().data(), top);
    stats.topSeconds = secondsSince(topStart);

    // The subtrees, largest first; each into its own wide nodes.
    Clock::time_point subtreeStart = Clock::now();
    buildSubtrees(p, sizedRefs.get().data(), subtrees);
    stats.subtreeSeconds = secondsSince(subtreeStart);

    // The top nodes, their boxes from their children's (children come after their parents); a
    // subtree's root is numbered after the top nodes, subtree j as top.size() + j.
    Clock::time_point flattenStart = Clock::now();
    Measure measure;
    auto topCount = std::uint32_t(top.size());
    std::vector<BvhNode> nodes(top.empty() ? 1 : top.size());
    Box rootBox;
    if (top.empty()) {
        // The root is a leaf or a subtree: an inner root with it as its first child and no second.
        const Subtree& s = subtrees[0];
        rootBox = s.box;
        if (s.nodes == 0) {
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
                    fill(n, side == 1, s.box, s.first, s.count, topCount + c, s.nodes == 0, measure);
                    topBoxes[k].grow(s.box);
                } else {
                    fill(n, side == 1, topBoxes[c], 0, 0, c, false, measure);
                    topBoxes[k].grow(topBoxes[c]);
                }
            }
            nodes[k] = n;
        }
        rootBox = topBoxes[0];
    }
    // SAH cost: Σ over inner nodes of area/root area times the cost of a visit, plus Σ over leaves
    // of area/root area times their primitives; the root's own visit included.
    double rootArea = std::max(area(rootBox.lower(), rootBox.upper()), 1e-30);
    double sum = measure.area;
    std::uint32_t count = topCount;
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
        count += s.nodes;
    }
    stats.sahCost = kTraversalCost + sum / rootArea;
    stats.nodes = count == 0 ? 1 : count;
    stats.flattenSeconds = secondsSince(flattenStart);

    // The top collapsed, the subtrees' wide nodes after it.
    Clock::time_point widenStart = Clock::now();
    widenTop(nodes, subtrees, rootBox, sizedWide.get(), stats);
    stats.widenSeconds = secondsSince(widenStart);
    stats.buildSeconds = secondsSince(start);
    return stats;
}

}  // namespace photon
