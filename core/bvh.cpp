#include "bvh.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "parallel.h"
#include "error.h"
#include "scene.h"
#include "shared/intersect.h"

namespace photon {
namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeaf = 4;
constexpr float kTraversalCost = 1.0f;     // of visiting a node, relative to testing a primitive
constexpr std::size_t kParallelBinning = 1u << 18;  // nodes this large bin on every core
constexpr std::size_t kSubtreeTask = 1u << 14;      // subtrees this large become tasks

struct Box {
    glm::vec3 lo{FLOAT_MAX};
    glm::vec3 hi{-FLOAT_MAX};

    void grow(const Box& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    void grow(glm::vec3 p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    float area() const {
        glm::vec3 d = glm::max(hi - lo, glm::vec3(0.0f));
        return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
    }
    bool empty() const { return lo.x > hi.x; }
};

// What the builder moves around: a primitive's box, its centroid and its reference (32 bytes,
// partitioned in place, so that every pass streams through memory).
struct Item {
    glm::vec3 lo;
    std::uint32_t ref;
    glm::vec3 hi;
    float pad;
    glm::vec3 centroid() const { return 0.5f * (lo + hi); }
};

// A node of the tree being built: a leaf (count > 0, items [first, first + count)) or an inner
// node with two children.
struct BuildNode {
    Box box;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    std::int32_t left = -1;
    std::int32_t right = -1;
};

// Per axis and bin: the primitives' box, their centroids' box, and how many there are.
struct Bins {
    Box box[3][kBins];
    Box centroids[3][kBins];
    std::uint32_t count[3][kBins] = {};

    void merge(const Bins& o) {
        for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < kBins; ++b) {
                box[a][b].grow(o.box[a][b]);
                centroids[a][b].grow(o.centroids[a][b]);
                count[a][b] += o.count[a][b];
            }
        }
    }
};

// The bin of a centroid coordinate; binning and partitioning both ask this, so that they agree.
struct Binning {
    glm::vec3 lo;
    glm::vec3 scale;  // bins per unit; 0 on an axis without extent

    explicit Binning(const Box& centroids) : lo(centroids.lo) {
        glm::vec3 extent = centroids.hi - centroids.lo;
        for (int a = 0; a < 3; ++a) {
            scale[a] = extent[a] > 0.0f ? float(kBins) * (1.0f - 1e-6f) / extent[a] : 0.0f;
        }
    }
    int bin(const glm::vec3& c, int axis) const {
        return std::clamp(int((c[axis] - lo[axis]) * scale[axis]), 0, kBins - 1);
    }
};

void binRange(const Item* items, std::size_t n, const Binning& binning, Bins& bins) {
    for (std::size_t i = 0; i < n; ++i) {
        glm::vec3 c = items[i].centroid();
        for (int a = 0; a < 3; ++a) {
            int b = binning.bin(c, a);
            bins.box[a][b].lo = glm::min(bins.box[a][b].lo, items[i].lo);
            bins.box[a][b].hi = glm::max(bins.box[a][b].hi, items[i].hi);
            bins.centroids[a][b].grow(c);
            bins.count[a][b] += 1;
        }
    }
}

// A subtree for a worker thread: the placeholder node it replaces and what it covers.
struct Task {
    std::int32_t node;
    std::uint32_t first;
    std::uint32_t count;
    Box box;
    Box centroids;
};

class Builder {
public:
    explicit Builder(std::vector<Item>& items) : items_(items) {}

    // Builds the subtree of items [first, first + count), whose box and centroid box are given;
    // returns its node index in `out`. With `tasks`, subtrees small enough become tasks instead.
    std::int32_t build(std::vector<BuildNode>& out, std::uint32_t first, std::uint32_t count, const Box& box,
                       const Box& centroids, bool parallel, std::vector<Task>* tasks) {
        BuildNode node;
        node.box = box;
        node.first = first;
        node.count = count;
        std::int32_t index = std::int32_t(out.size());
        out.push_back(node);
        if (count <= 1) {
            return index;
        }
        if (tasks != nullptr && count <= kSubtreeTask * 4) {
            tasks->push_back({index, first, count, box, centroids});
            return index;
        }
        Split s;
        if (!chooseSplit(first, count, box, centroids, parallel, s)) {
            return index;  // a leaf
        }
        std::int32_t left = build(out, first, s.index - first, s.leftBox, s.leftCentroids, parallel, tasks);
        std::int32_t right = build(out, s.index, first + count - s.index, s.rightBox, s.rightCentroids, parallel, tasks);
        out[std::size_t(index)].left = left;
        out[std::size_t(index)].right = right;
        out[std::size_t(index)].count = 0;
        return index;
    }

private:
    struct Split {
        std::uint32_t index = 0;  // the first item of the right side
        Box leftBox, leftCentroids, rightBox, rightCentroids;
    };

    // Children's boxes of a split by order (no bins): measured.
    void measure(std::uint32_t first, std::uint32_t count, Box& box, Box& centroids) const {
        for (std::uint32_t i = first; i < first + count; ++i) {
            box.grow(Box{items_[i].lo, items_[i].hi});
            centroids.grow(items_[i].centroid());
        }
    }

    bool splitByOrder(std::uint32_t first, std::uint32_t count, Split& s) const {
        s.index = first + count / 2;
        measure(first, s.index - first, s.leftBox, s.leftCentroids);
        measure(s.index, first + count - s.index, s.rightBox, s.rightCentroids);
        return true;
    }

    // The SAH split of items [first, first + count): partitions them and returns true, or false if
    // a leaf is cheaper.
    bool chooseSplit(std::uint32_t first, std::uint32_t count, const Box& box, const Box& centroids, bool parallel,
                     Split& s) {
        Binning binning(centroids);
        Bins bins;
        if (parallel && count >= kParallelBinning) {
            std::size_t chunks = std::max<std::size_t>(1, count / (kParallelBinning / 4));
            std::vector<Bins> partial(chunks);
            parallelFor(chunks, 1, [&](std::size_t a, std::size_t b) {
                for (std::size_t c = a; c < b; ++c) {
                    std::size_t begin = count * c / chunks;
                    std::size_t end = count * (c + 1) / chunks;
                    binRange(items_.data() + first + begin, end - begin, binning, partial[c]);
                }
            });
            for (const Bins& p : partial) {
                bins.merge(p);
            }
        } else {
            binRange(items_.data() + first, count, binning, bins);
        }
        float bestCost = FLOAT_MAX;
        int bestAxis = -1;
        int bestBin = 0;
        for (int a = 0; a < 3; ++a) {
            if (binning.scale[a] == 0.0f) {
                continue;
            }
            // Sweep from the right: the area and count of bins [b, kBins).
            float rightArea[kBins];
            std::uint32_t rightCount[kBins];
            Box acc;
            std::uint32_t n = 0;
            for (int b = kBins - 1; b > 0; --b) {
                acc.grow(bins.box[a][b]);
                n += bins.count[a][b];
                rightArea[b] = acc.area();
                rightCount[b] = n;
            }
            acc = Box{};
            n = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                acc.grow(bins.box[a][b]);
                n += bins.count[a][b];
                if (n == 0 || rightCount[b + 1] == 0) {
                    continue;
                }
                float cost = acc.area() * float(n) + rightArea[b + 1] * float(rightCount[b + 1]);
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = a;
                    bestBin = b;
                }
            }
        }
        if (bestAxis < 0) {
            // Every centroid in one point: split by order, so that leaves stay small.
            return count > kMaxLeaf && splitByOrder(first, count, s);
        }
        float parentArea = box.area();
        float splitCost = kTraversalCost + (parentArea > 0.0f ? bestCost / parentArea : 0.0f);
        if (count <= kMaxLeaf && float(count) <= splitCost) {
            return false;
        }
        for (int b = 0; b < kBins; ++b) {
            Box& box2 = b <= bestBin ? s.leftBox : s.rightBox;
            Box& centroids2 = b <= bestBin ? s.leftCentroids : s.rightCentroids;
            box2.grow(bins.box[bestAxis][b]);
            centroids2.grow(bins.centroids[bestAxis][b]);
        }
        Item* begin = items_.data() + first;
        Item* middle = std::partition(begin, begin + count, [&](const Item& item) {
            return binning.bin(item.centroid(), bestAxis) <= bestBin;
        });
        s.index = first + std::uint32_t(middle - begin);
        if (s.index == first || s.index == first + count) {
            s = Split{};
            return splitByOrder(first, count, s);
        }
        return true;
    }

    std::vector<Item>& items_;
};

// The hierarchy in the shared layout: every inner build node a BvhNode holding both children's
// boxes, nodes in depth-first order (the root first, a node's first child next to it).
struct Flattener {
    const std::vector<BuildNode>& tree;
    const std::vector<Item>& items;
    std::vector<BvhNode>& nodes;
    std::vector<std::uint32_t>& refs;
    BvhStats& stats;
    float rootArea;

    void child(const BuildNode& c, glm::vec3& lower, glm::vec3& upper, std::uint32_t& index, std::uint32_t& count,
               std::uint32_t depth) {
        lower = c.box.lo;
        upper = c.box.hi;
        if (c.left < 0 && c.count == 0) {
            // No child: a point beyond every ray's reach (an inverted box would look full to the
            // slab test, which sorts its planes).
            lower = glm::vec3(FLOAT_MAX);
            upper = glm::vec3(FLOAT_MAX);
            index = 0;
            count = 0;
        } else if (c.left < 0) {
            index = std::uint32_t(refs.size());
            count = c.count;
            for (std::uint32_t i = c.first; i < c.first + c.count; ++i) {
                refs.push_back(items[i].ref);
            }
            stats.leaves += 1;
            stats.sahCost += rootArea > 0.0f ? double(c.box.area()) / rootArea * double(c.count) : double(c.count);
        } else {
            count = 0;
            index = flatten(c, depth + 1);
        }
    }

    std::uint32_t flatten(const BuildNode& n, std::uint32_t depth) {
        std::uint32_t index = std::uint32_t(nodes.size());
        nodes.push_back(BvhNode{});
        stats.depth = std::max(stats.depth, depth);
        stats.sahCost += rootArea > 0.0f ? double(n.box.area()) / rootArea * kTraversalCost : kTraversalCost;
        BvhNode node{};
        child(tree[std::size_t(n.left)], node.lowerA, node.upperA, node.childA, node.countA, depth);
        child(tree[std::size_t(n.right)], node.lowerB, node.upperB, node.childB, node.countB, depth);
        nodes[index] = node;
        return index;
    }
};

Box quadBox(const Quad& q) {
    Box b;
    b.grow(q.corner);
    b.grow(q.corner + q.edgeU);
    b.grow(q.corner + q.edgeV);
    b.grow(q.corner + q.edgeU + q.edgeV);
    return b;
}

}  // namespace

BvhStats buildBvh(const Scene& scene, std::vector<BvhNode>& nodes, std::vector<std::uint32_t>& refs) {
    auto start = std::chrono::steady_clock::now();
    nodes.clear();
    refs.clear();
    BvhStats stats;
    std::vector<Item> items;
    items.reserve(scene.spheres.size() + scene.quads.size() + scene.triangles.size());
    auto add = [&](const Box& b, std::uint32_t kind, std::size_t index) {
        items.push_back({b.lo, (kind << PRIMITIVE_INDEX_BITS) | std::uint32_t(index), b.hi, 0.0f});
    };
    for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
        const Sphere& s = scene.spheres[i];
        add(Box{s.center - glm::vec3(s.radius), s.center + glm::vec3(s.radius)}, PRIM_SPHERE, i);
    }
    for (std::size_t i = 0; i < scene.quads.size(); ++i) {
        add(quadBox(scene.quads[i]), PRIM_QUAD, i);
    }
    items.resize(items.size() + scene.triangles.size());
    std::size_t base = items.size() - scene.triangles.size();
    parallelFor(scene.triangles.size(), 65536, [&](std::size_t a, std::size_t b) {
        for (std::size_t i = a; i < b; ++i) {
            const Triangle& t = scene.triangles[i];
            items[base + i] = {glm::min(t.v0, glm::min(t.v1, t.v2)), (PRIM_TRIANGLE << PRIMITIVE_INDEX_BITS) | std::uint32_t(i),
                               glm::max(t.v0, glm::max(t.v1, t.v2)), 0.0f};
        }
    });
    stats.primitives = std::uint32_t(items.size());
    if (items.empty()) {
        return stats;
    }

    // The top of the tree on this thread (binning on every core), then its subtrees as tasks.
    Box box;
    Box centroids;
    for (const Item& item : items) {
        box.grow(Box{item.lo, item.hi});
        centroids.grow(item.centroid());
    }
    Builder builder(items);
    std::vector<BuildNode> tree;
    std::vector<Task> tasks;
    bool split = items.size() > kSubtreeTask * 4;
    builder.build(tree, 0, std::uint32_t(items.size()), box, centroids, true, split ? &tasks : nullptr);
    std::vector<std::vector<BuildNode>> subtrees(tasks.size());
    std::size_t threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> workers;
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::mutex failureMutex;
    for (std::size_t w = 0; w < std::min(threads, tasks.size()); ++w) {
        workers.emplace_back([&] {
            try {
                for (std::size_t t = next++; t < tasks.size(); t = next++) {
                    Builder sub(items);
                    sub.build(subtrees[t], tasks[t].first, tasks[t].count, tasks[t].box, tasks[t].centroids, false, nullptr);
                }
            } catch (...) {
                std::lock_guard<std::mutex> lock(failureMutex);
                failure = std::current_exception();
                next = tasks.size();
            }
        });
    }
    for (std::thread& w : workers) {
        w.join();
    }
    if (failure) {
        std::rethrow_exception(failure);
    }
    // Each task's subtree replaces its placeholder: its root in place, the rest appended.
    for (std::size_t t = 0; t < tasks.size(); ++t) {
        std::vector<BuildNode>& sub = subtrees[t];
        std::int32_t offset = std::int32_t(tree.size()) - 1;
        auto shift = [&](std::int32_t i) { return i < 0 ? i : i + offset; };
        for (std::size_t i = 0; i < sub.size(); ++i) {
            BuildNode n = sub[i];
            n.left = shift(n.left);
            n.right = shift(n.right);
            if (i == 0) {
                tree[std::size_t(tasks[t].node)] = n;
            } else {
                tree.push_back(n);
            }
        }
    }

    // The root of the shared layout is an inner node: a lone leaf becomes its first child.
    if (tree[0].left < 0) {
        BuildNode leaf = tree[0];
        BuildNode empty;
        empty.count = 0;
        empty.left = -1;
        tree.push_back(leaf);
        tree.push_back(empty);
        tree[0].left = std::int32_t(tree.size() - 2);
        tree[0].right = std::int32_t(tree.size() - 1);
    }
    nodes.reserve(items.size() / 2 + 1);
    refs.reserve(items.size());
    Flattener flat{tree, items, nodes, refs, stats, tree[0].box.area()};
    flat.flatten(tree[0], 1);
    stats.nodes = std::uint32_t(nodes.size());
    if (stats.depth >= BVH_STACK_SIZE) {
        throw InputError("the scene's bounding volume hierarchy is " + std::to_string(stats.depth) +
                         " levels deep, more than the " + std::to_string(BVH_STACK_SIZE) +
                         " its traversal can follow (many primitives in one place?)");
    }
    stats.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return stats;
}

}  // namespace photon
