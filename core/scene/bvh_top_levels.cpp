// Phase 2 of the BVH build (core/scene/bvh.cpp): the top levels, nodes larger than a subtree,
// split a level at a time, each level's partition spread over every thread in fixed chunks.
#include "core/scene/bvh_build.h"
#include "core/system/parallel.h"

namespace photon::bvh_build {
namespace {

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

}  // namespace

std::vector<Subtree> buildTopLevels(const Primitives& p, std::uint32_t count, std::uint32_t* scratch,
                                   std::vector<TopNode>& nodes) {
    return TopLevels(p, scratch, subtreeSize(count)).run(count, nodes);
}

}  // namespace photon::bvh_build
