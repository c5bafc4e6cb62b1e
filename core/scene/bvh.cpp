#include "core/scene/bvh.h"

#include <emmintrin.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

#include "core/scene/scene.h"
#include "core/system/error.h"
#include "core/system/parallel.h"
#include "shared/intersect.h"

namespace photon {
namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeaf = 4;
constexpr float kTraversalCost = 1.0f;         // of visiting a node, relative to testing a primitive
constexpr std::uint32_t kSampled = 1u << 14;   // nodes larger than this bin a sample of this many
constexpr std::uint32_t kSubtree = 1u << 15;   // nodes this small are built whole by one thread

// A primitive as the builder moves it: its box as two SSE registers, the reference in the lower
// corner's fourth lane (32 bytes, partitioned in place, so that every pass streams through memory).
struct alignas(16) Item {
    __m128 lo;
    __m128 hi;
    std::uint32_t ref() const { return std::uint32_t(_mm_cvtsi128_si32(_mm_castps_si128(_mm_shuffle_ps(lo, lo, 3)))); }
};

float lane(__m128 v, int i) {
    alignas(16) float f[4];
    _mm_store_ps(f, v);
    return f[i];
}

struct Box {
    __m128 lo = _mm_set1_ps(FLOAT_MAX);
    __m128 hi = _mm_set1_ps(-FLOAT_MAX);

    void grow(__m128 l, __m128 h) {
        lo = _mm_min_ps(lo, l);
        hi = _mm_max_ps(hi, h);
    }
    void grow(const Box& b) { grow(b.lo, b.hi); }
    float area() const {
        alignas(16) float d[4];
        _mm_store_ps(d, _mm_max_ps(_mm_sub_ps(hi, lo), _mm_setzero_ps()));
        return 2.0f * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0]);
    }
    glm::vec3 lower() const { return {lane(lo, 0), lane(lo, 1), lane(lo, 2)}; }
    glm::vec3 upper() const { return {lane(hi, 0), lane(hi, 1), lane(hi, 2)}; }
};

// Centroids are kept doubled (lo + hi): the same order, one multiply less per item.
__m128 doubledCentroid(const Item& item) { return _mm_add_ps(item.lo, item.hi); }

// The work of one node: its items, box, doubled-centroid box and depth.
struct Range {
    std::uint32_t first;
    std::uint32_t count;
    Box box;
    Box centroids;
    std::uint32_t depth = 1;
};

// Below this depth nodes split at the median along their longest axis instead, so that no input,
// however clustered, makes the hierarchy deeper than the traversal's stack.
constexpr std::uint32_t kMedianDepth = 32;

class Builder {
public:
    explicit Builder(std::vector<Item>& items) : items_(items) {}

    // Splits a range by the surface area heuristic along the longest axis of its centroids, or
    // returns false if a leaf is cheaper. Partitions the items and measures both sides.
    bool split(const Range& r, Range& left, Range& right) const {
        if (r.count <= kMaxLeaf) {
            return false;  // small enough: a leaf, without weighing a split
        }
        glm::vec3 clo = Box{r.centroids}.lower();
        glm::vec3 chi = Box{r.centroids}.upper();
        glm::vec3 extent = chi - clo;
        int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        if (!(extent[axis] > 0.0f) || r.depth >= kMedianDepth) {
            return r.count > kMaxLeaf && splitAtMedian(r, axis, left, right);
        }
        float lo = clo[axis];
        float scale = float(kBins) * (1.0f - 1e-6f) / extent[axis];
        auto binOf = [&](const Item& item) {
            // Near the float limit a doubled centroid overflows to ±inf and (c - lo) · scale can be
            // NaN: such items go to the first bin, never through an undefined conversion.
            float x = (lane(doubledCentroid(item), axis) - lo) * scale;
            return x >= 0.0f ? (x < float(kBins - 1) ? int(x) : kBins - 1) : 0;
        };
        // Bin every item, or a regular sample of a large node (the split need only be nearly best;
        // the partition below measures the children exactly).
        Box bins[kBins];
        std::uint32_t counts[kBins] = {};
        std::uint32_t stride = r.count > kSampled ? r.count / kSampled : 1;
        for (std::uint32_t i = r.first; i < r.first + r.count; i += stride) {
            int b = binOf(items_[i]);
            bins[b].grow(items_[i].lo, items_[i].hi);
            counts[b] += 1;
        }
        float rightArea[kBins];
        std::uint32_t rightCount[kBins];
        Box acc;
        std::uint32_t n = 0;
        for (int b = kBins - 1; b > 0; --b) {
            acc.grow(bins[b]);
            n += counts[b];
            rightArea[b] = acc.area();
            rightCount[b] = n;
        }
        acc = Box{};
        n = 0;
        float bestCost = FLOAT_MAX;
        int bestBin = -1;
        for (int b = 0; b < kBins - 1; ++b) {
            acc.grow(bins[b]);
            n += counts[b];
            if (n == 0 || rightCount[b + 1] == 0) {
                continue;
            }
            float cost = acc.area() * float(n) + rightArea[b + 1] * float(rightCount[b + 1]);
            if (cost < bestCost) {
                bestCost = cost;
                bestBin = b;
            }
        }
        if (bestBin < 0) {
            return r.count > kMaxLeaf && splitAtMedian(r, axis, left, right);
        }

        // Hoare's partition, measuring each side as its items settle.
        left = Range{r.first, 0, {}, {}, r.depth + 1};
        right = Range{0, 0, {}, {}, r.depth + 1};
        std::uint32_t i = r.first;
        std::uint32_t j = r.first + r.count;  // one past the last unsettled item
        auto settleLeft = [&](const Item& item) {
            left.box.grow(item.lo, item.hi);
            __m128 c = doubledCentroid(item);
            left.centroids.grow(c, c);
        };
        auto settleRight = [&](const Item& item) {
            right.box.grow(item.lo, item.hi);
            __m128 c = doubledCentroid(item);
            right.centroids.grow(c, c);
        };
        while (true) {
            while (i < j && binOf(items_[i]) <= bestBin) {
                settleLeft(items_[i]);
                ++i;
            }
            while (i < j && binOf(items_[j - 1]) > bestBin) {
                settleRight(items_[j - 1]);
                --j;
            }
            if (i >= j) {
                break;
            }
            std::swap(items_[i], items_[j - 1]);
            settleLeft(items_[i]);
            settleRight(items_[j - 1]);
            ++i;
            --j;
        }
        left.count = i - r.first;
        right.first = i;
        right.count = r.first + r.count - i;
        if (left.count == 0 || right.count == 0) {
            return splitAtMedian(r, axis, left, right);
        }
        return true;
    }

private:
    // Half the items on each side, split at the median of their centroids along `axis`.
    bool splitAtMedian(const Range& r, int axis, Range& left, Range& right) const {
        Item* begin = items_.data() + r.first;
        std::nth_element(begin, begin + r.count / 2, begin + r.count, [axis](const Item& a, const Item& b) {
            return lane(doubledCentroid(a), axis) < lane(doubledCentroid(b), axis);
        });
        left = Range{r.first, r.count / 2, {}, {}, r.depth + 1};
        right = Range{r.first + r.count / 2, r.count - r.count / 2, {}, {}, r.depth + 1};
        for (Range* side : {&left, &right}) {
            for (std::uint32_t i = side->first; i < side->first + side->count; ++i) {
                side->box.grow(items_[i].lo, items_[i].hi);
                __m128 c = doubledCentroid(items_[i]);
                side->centroids.grow(c, c);
            }
        }
        return true;
    }

    std::vector<Item>& items_;
};

// Where a node's child goes: node `node`'s first (A) or second (B) child.
struct Slot {
    std::uint32_t node = NONE;  // NONE: the root itself
    bool second = false;
};

// An absent child: a point beyond every ray's reach (an inverted box would look full to the slab
// test, which sorts its planes).
BvhNode emptyNode() {
    BvhNode n{};
    n.lowerA = n.upperA = n.lowerB = n.upperB = glm::vec3(FLOAT_MAX);
    return n;
}

bool absent(glm::vec3 lower) { return lower.x == FLOAT_MAX; }

// Writes a child into its parent's slot: a leaf (its items, which are its primitive references in
// item order) or inner node `index`.
void fill(BvhNode& parent, bool second, const Range& child, std::uint32_t index, bool leaf) {
    (second ? parent.lowerB : parent.lowerA) = child.box.lower();
    (second ? parent.upperB : parent.upperA) = child.box.upper();
    (second ? parent.childB : parent.childA) = leaf ? child.first : index;
    (second ? parent.countB : parent.countA) = leaf ? child.count : 0;
}

// A subtree built by one thread, its nodes indexed from 0, moved into the whole at the end.
struct Subtree {
    Slot slot;                   // where its root goes in the whole
    Range root;
    std::vector<BvhNode> nodes;  // empty: the root is a leaf
};

// Builds the hierarchy on every core: large nodes are split by whichever thread takes them from a
// queue (their children go back on it), small ones become whole subtrees of one thread. Inner nodes
// are written straight into the shared layout; a child's box and place are filled into its parent
// once the child is known to be a leaf or an inner node.
class ParallelBuild {
public:
    ParallelBuild(std::vector<Item>& items, std::vector<BvhNode>& nodes) : builder_(items), nodes_(nodes) {}

    void run(const Range& root) {
        nodes_.reserve(root.count / 2 + 2);
        queue_.push_back({Slot{}, root});
        pending_ = 1;
        std::size_t threads = std::max(1u, std::thread::hardware_concurrency());
        std::vector<std::thread> workers;
        for (std::size_t t = 0; t < threads; ++t) {
            workers.emplace_back([this] { work(); });
        }
        for (std::thread& w : workers) {
            w.join();
        }
        if (failure_) {
            std::rethrow_exception(failure_);
        }
        if (nodes_.empty()) {
            // The root is a leaf: an inner root with it as its first child and no second.
            nodes_.push_back(emptyNode());
            fill(nodes_[0], false, rootLeaf_, 0, true);
        }
        for (Subtree& s : subtrees_) {
            auto offset = std::uint32_t(nodes_.size());
            fill(nodes_[s.slot.node], s.slot.second, s.root, offset, s.nodes.empty());
            for (BvhNode n : s.nodes) {
                n.childA += n.countA == 0 && !absent(n.lowerA) ? offset : 0;
                n.childB += n.countB == 0 && !absent(n.lowerB) ? offset : 0;
                nodes_.push_back(n);
            }
        }
    }

private:
    struct Job {
        Slot slot;
        Range range;
    };

    void buildSubtree(Subtree& s) const {
        Range left;
        Range right;
        if (s.root.count <= 1 || !builder_.split(s.root, left, right)) {
            return;  // a leaf
        }
        s.nodes.push_back(emptyNode());
        std::vector<std::pair<Slot, Range>> stack{{Slot{0, true}, right}, {Slot{0, false}, left}};
        while (!stack.empty()) {
            auto [slot, r] = stack.back();
            stack.pop_back();
            if (r.count <= 1 || !builder_.split(r, left, right)) {
                fill(s.nodes[slot.node], slot.second, r, 0, true);
                continue;
            }
            auto index = std::uint32_t(s.nodes.size());
            s.nodes.push_back(emptyNode());
            fill(s.nodes[slot.node], slot.second, r, index, false);
            stack.push_back({Slot{index, true}, right});
            stack.push_back({Slot{index, false}, left});
        }
    }

    void work() {
        try {
            while (true) {
                Job job;
                {
                    std::unique_lock<std::mutex> lock(mutex_);
                    ready_.wait(lock, [&] { return !queue_.empty() || pending_ == 0; });
                    if (queue_.empty()) {
                        return;
                    }
                    job = queue_.front();
                    queue_.pop_front();
                }
                Range left;
                Range right;
                if (job.range.count <= kSubtree && job.slot.node != NONE) {
                    Subtree s{job.slot, job.range, {}};
                    buildSubtree(s);
                    std::lock_guard<std::mutex> lock(mutex_);
                    subtrees_.push_back(std::move(s));
                    pending_ -= 1;
                } else if (job.range.count > 1 && builder_.split(job.range, left, right)) {
                    std::lock_guard<std::mutex> lock(mutex_);
                    auto index = std::uint32_t(nodes_.size());
                    nodes_.push_back(emptyNode());
                    if (job.slot.node != NONE) {
                        fill(nodes_[job.slot.node], job.slot.second, job.range, index, false);
                    }
                    queue_.push_back({Slot{index, false}, left});
                    queue_.push_back({Slot{index, true}, right});
                    pending_ += 1;  // two more, this one done
                } else {
                    std::lock_guard<std::mutex> lock(mutex_);
                    if (job.slot.node != NONE) {
                        fill(nodes_[job.slot.node], job.slot.second, job.range, 0, true);
                    } else {
                        rootLeaf_ = job.range;
                    }
                    pending_ -= 1;
                }
                ready_.notify_all();
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(mutex_);
            failure_ = std::current_exception();
            queue_.clear();
            pending_ = 0;
            ready_.notify_all();
        }
    }

    Builder builder_;
    std::vector<BvhNode>& nodes_;
    std::mutex mutex_;
    std::condition_variable ready_;
    std::deque<Job> queue_;
    std::size_t pending_ = 0;  // jobs queued or running
    std::vector<Subtree> subtrees_;
    Range rootLeaf_{0, 0, {}, {}};
    std::exception_ptr failure_;
};

// Depth, leaves and SAH cost of the finished hierarchy: Σ over inner nodes of area/root area times
// the cost of a visit, plus Σ over leaves of area/root area times their primitives.
void measure(const std::vector<BvhNode>& nodes, BvhStats& stats) {
    auto area = [](glm::vec3 lo, glm::vec3 hi) {
        glm::dvec3 d = glm::max(glm::dvec3(hi) - glm::dvec3(lo), glm::dvec3(0.0));
        return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
    };
    const BvhNode& root = nodes[0];
    glm::vec3 lo = absent(root.lowerB) ? root.lowerA : glm::min(root.lowerA, root.lowerB);
    glm::vec3 hi = absent(root.lowerB) ? root.upperA : glm::max(root.upperA, root.upperB);
    double rootArea = std::max(area(lo, hi), 1e-30);
    stats.sahCost = kTraversalCost;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> stack{{0, 1}};
    while (!stack.empty()) {
        auto [index, depth] = stack.back();
        stack.pop_back();
        const BvhNode& n = nodes[index];
        stats.depth = std::max(stats.depth, depth);
        for (int c = 0; c < 2; ++c) {
            glm::vec3 clo = c ? n.lowerB : n.lowerA;
            glm::vec3 chi = c ? n.upperB : n.upperA;
            std::uint32_t count = c ? n.countB : n.countA;
            if (absent(clo)) {
                continue;
            }
            double share = area(clo, chi) / rootArea;
            if (count > 0) {
                stats.leaves += 1;
                stats.sahCost += share * double(count);
            } else {
                stats.sahCost += share * kTraversalCost;
                stack.push_back({c ? n.childB : n.childA, depth + 1});
            }
        }
    }
}

Item makeItem(glm::vec3 lo, glm::vec3 hi, std::uint32_t ref) {
    float bits;
    std::memcpy(&bits, &ref, 4);
    return {_mm_set_ps(bits, lo.z, lo.y, lo.x), _mm_set_ps(0.0f, hi.z, hi.y, hi.x)};
}

}  // namespace

BvhStats buildBvh(const Scene& scene, std::vector<BvhNode>& nodes, std::vector<std::uint32_t>& refs) {
    auto start = std::chrono::steady_clock::now();
    nodes.clear();
    refs.clear();
    BvhStats stats;
    std::vector<Item> items(scene.spheres.size() + scene.quads.size() + scene.triangles.size());
    std::size_t next = 0;
    for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
        const Sphere& s = scene.spheres[i];
        items[next++] = makeItem(s.center - glm::vec3(s.radius), s.center + glm::vec3(s.radius),
                                 (PRIM_SPHERE << PRIMITIVE_INDEX_BITS) | std::uint32_t(i));
    }
    for (std::size_t i = 0; i < scene.quads.size(); ++i) {
        const Quad& q = scene.quads[i];
        glm::vec3 corners[4] = {q.corner, q.corner + q.edgeU, q.corner + q.edgeV, q.corner + q.edgeU + q.edgeV};
        glm::vec3 lo = corners[0];
        glm::vec3 hi = corners[0];
        for (glm::vec3 c : corners) {
            lo = glm::min(lo, c);
            hi = glm::max(hi, c);
        }
        items[next++] = makeItem(lo, hi, (PRIM_QUAD << PRIMITIVE_INDEX_BITS) | std::uint32_t(i));
    }
    std::size_t base = next;
    std::size_t chunks = std::max<std::size_t>(1, scene.triangles.size() / 65536);
    std::vector<Box> boxes(chunks + 1);
    std::vector<Box> centroidBoxes(chunks + 1);
    // The triangles' items, and with them the root's box and centroid box, on every core.
    parallelFor(chunks, 1, [&](std::size_t a, std::size_t b) {
        for (std::size_t c = a; c < b; ++c) {
            std::size_t n = scene.triangles.size();
            for (std::size_t i = n * c / chunks; i < n * (c + 1) / chunks; ++i) {
                const Triangle& t = scene.triangles[i];
                Item item = makeItem(glm::min(t.v0, glm::min(t.v1, t.v2)), glm::max(t.v0, glm::max(t.v1, t.v2)),
                                     (PRIM_TRIANGLE << PRIMITIVE_INDEX_BITS) | std::uint32_t(i));
                items[base + i] = item;
                boxes[c].grow(item.lo, item.hi);
                __m128 centroid = doubledCentroid(item);
                centroidBoxes[c].grow(centroid, centroid);
            }
        }
    });
    for (std::size_t i = 0; i < base; ++i) {
        boxes[chunks].grow(items[i].lo, items[i].hi);
        __m128 centroid = doubledCentroid(items[i]);
        centroidBoxes[chunks].grow(centroid, centroid);
    }
    stats.primitives = std::uint32_t(items.size());
    if (items.empty()) {
        return stats;
    }
    Range root{0, std::uint32_t(items.size()), {}, {}};
    for (std::size_t c = 0; c <= chunks; ++c) {
        root.box.grow(boxes[c]);
        root.centroids.grow(centroidBoxes[c]);
    }
    auto since = [](std::chrono::steady_clock::time_point t) {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    };
    stats.prepareSeconds = since(start);
    auto built = std::chrono::steady_clock::now();
    ParallelBuild(items, nodes).run(root);
    stats.topSeconds = since(built);  // top levels and subtrees together: one queue
    auto flattened = std::chrono::steady_clock::now();
    refs.resize(items.size());
    parallelFor(items.size(), 65536, [&](std::size_t a, std::size_t b) {
        for (std::size_t i = a; i < b; ++i) {
            refs[i] = items[i].ref();
        }
    });
    stats.nodes = std::uint32_t(nodes.size());
    measure(nodes, stats);
    if (stats.depth >= BVH_STACK_SIZE) {
        throw InputError("the scene's bounding volume hierarchy is " + std::to_string(stats.depth) +
                         " levels deep, more than the " + std::to_string(BVH_STACK_SIZE) +
                         " its traversal can follow (many primitives in one place?)");
    }
    stats.flattenSeconds = since(flattened);
    stats.buildSeconds = since(start);
    return stats;
}

}  // namespace photon
