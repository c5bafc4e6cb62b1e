// The binary hierarchy collapsed into four-wide nodes with quantized boxes (Ylitie, Karras &
// Laine 2017 collapse eight-wide by an SAH-optimal assignment; four-wide, the greedy rule of
// Wald et al. 2008 comes within a few percent of it): a wide node starts with its binary node's
// two children and replaces the inner child of the largest surface by that child's own two until
// it holds four or only leaves. A wide node's children come next to each other in the array, in
// breadth-first order of the levels above the subtrees and of each subtree.
//
// The top levels are collapsed on one thread until there are enough wide nodes left to collapse
// for every thread; each of those is then the root of a subtree collapsed by one thread into its
// own array, and the arrays are concatenated in order, so the nodes do not depend on the threads.
//
// Quantization: per axis, child boxes are origin + q · 2^(e − 127) for bytes q, the origin the
// node's lower corner and e the least exponent whose 255 steps reach its upper corner. Every plane
// is rounded outwards and checked in the float arithmetic the traversal decodes it with (q · 2^k
// is exact, so a fused multiply-add gives the same sum), so a decoded box always holds its child.
#include "core/scene/bvh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "core/scene/scene.h"
#include "core/scene/sized_on_helper.h"
#include "core/system/error.h"
#include "core/system/parallel.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;

// A child as the binary tree has it: a box and an inner node or a leaf's references.
struct Child {
    glm::vec3 lower;
    glm::vec3 upper;
    std::uint32_t index;  // binary node (inner) or first reference (leaf)
    std::uint32_t count;  // 0: inner
};

// Reads the binary nodes as one array would hold them (BinaryBvh::node), remembering the subtree
// it read last.
struct BinaryReader {
    const BinaryBvh& tree;
    std::size_t hint = 0;
    BvhNode operator[](std::uint32_t g) { return tree.node(g, hint); }
};

double surface(glm::vec3 lo, glm::vec3 hi) {
    glm::dvec3 d = glm::max(glm::dvec3(hi) - glm::dvec3(lo), glm::dvec3(0.0));
    return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// The binary node's present children.
int binaryChildren(const BvhNode& n, Child* out) {
    int k = 0;
    if (n.lowerA.x != FLOAT_MAX) {
        out[k++] = Child{n.lowerA, n.upperA, n.childA, n.countA};
    }
    if (n.lowerB.x != FLOAT_MAX) {
        out[k++] = Child{n.lowerB, n.upperB, n.childB, n.countB};
    }
    return k;
}

// The children of binary node `b` as a wide node takes them (the largest inner one opened until
// there are BVH_WIDTH); returns how many.
int collapse(BinaryReader& binary, std::uint32_t b, Child* children) {
    int k = binaryChildren(binary[b], children);
    while (k < int(BVH_WIDTH)) {
        int largest = -1;
        double largestArea = -1.0;
        for (int i = 0; i < k; ++i) {
            double a = surface(children[i].lower, children[i].upper);
            if (children[i].count == 0 && a > largestArea) {
                largest = i;
                largestArea = a;
            }
        }
        if (largest < 0) {
            break;
        }
        Child opened[2];
        int m = binaryChildren(binary[children[largest].index], opened);
        // The opened node's place goes to its first child, its second comes right after.
        for (int i = k; i > largest + 1; --i) {
            children[i + m - 2] = children[i - 1];
        }
        for (int i = 0; i < m; ++i) {
            children[largest + i] = opened[i];
        }
        k += m - 1;
    }
    return k;
}

// 2^(e − 127) for a biased exponent e in [1, 254]: the float of those exponent bits.
float scaleOf(std::uint32_t e) {
    std::uint32_t bits = e << 23;
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

// Decodes exactly as shared/intersect.h does.
float decode(float origin, std::uint32_t q, float scale) { return origin + float(q) * scale; }

// The least exponent whose 255 steps from `lo` reach `hi`.
std::uint32_t stepExponent(float lo, float hi) {
    float extent = (hi - lo) * (1.0f / 255.0f);
    std::uint32_t bits;
    std::memcpy(&bits, &extent, sizeof bits);
    std::uint32_t e = std::clamp(std::uint32_t(bits >> 23) + 1u, 1u, 254u);  // 2^(e − 127) > extent / 255
    while (e > 1 && decode(lo, 255, scaleOf(e - 1)) >= hi) {
        --e;
    }
    while (e < 254 && decode(lo, 255, scaleOf(e)) < hi) {
        ++e;
    }
    return e;
}

void quantize(const Child* children, int k, WideBvhNode& n) {
    glm::vec3 lo(FLOAT_MAX);
    glm::vec3 hi(-FLOAT_MAX);
    for (int i = 0; i < k; ++i) {
        lo = glm::min(lo, children[i].lower);
        hi = glm::max(hi, children[i].upper);
    }
    n.origin = lo;
    n.scales = 0;
    n.lowerX = n.lowerY = n.lowerZ = 0;
    n.upperX = n.upperY = n.upperZ = 0;
    std::uint32_t* lower[3] = {&n.lowerX, &n.lowerY, &n.lowerZ};
    std::uint32_t* upper[3] = {&n.upperX, &n.upperY, &n.upperZ};
    for (int a = 0; a < 3; ++a) {
        std::uint32_t e = stepExponent(lo[a], hi[a]);
        float scale = scaleOf(e);
        float inverse = scaleOf(254u - e);  // 1 / scale, exactly
        n.scales |= e << (8 * a);
        for (int i = 0; i < k; ++i) {
            // A first guess from the float difference, then moved outwards until the decoded
            // plane is outside the child (it is off by a step at most).
            float ql = std::floor((children[i].lower[a] - lo[a]) * inverse);
            float qh = std::ceil((children[i].upper[a] - lo[a]) * inverse);
            auto qlo = std::uint32_t(std::clamp(ql, 0.0f, 255.0f));
            auto qhi = std::uint32_t(std::clamp(qh, 0.0f, 255.0f));
            while (qlo > 0 && decode(lo[a], qlo, scale) > children[i].lower[a]) {
                --qlo;
            }
            while (qhi < 255 && decode(lo[a], qhi, scale) < children[i].upper[a]) {
                ++qhi;
            }
            *lower[a] |= qlo << (8 * i);
            *upper[a] |= qhi << (8 * i);
        }
    }
}

// What the statistics add up over a part of the wide tree.
struct WideMeasure {
    double area = 0.0;  // Σ over children of their decoded area × (a leaf's primitives, or 1)
    std::uint32_t depth = 0;
    std::uint32_t stack = 0;
};

// A wide node to make: from binary node `binary`, at `wide`, below ancestors that leave at most
// `stack` entries on the traversal's stack, `depth` wide nodes from the root (the root: 1).
struct Pending {
    std::uint32_t binary;
    std::uint32_t wide;
    std::uint32_t stack;
    std::uint32_t depth;
};

// Makes wide node `p` into nodes[p.wide], placing its inner children at the end of `nodes` and
// adding them to `queue`.
void makeNode(BinaryReader& binary, Pending p, std::vector<WideBvhNode>& nodes, std::vector<Pending>& queue,
              WideMeasure& m) {
    Child children[BVH_WIDTH];
    int k = collapse(binary, p.binary, children);
    WideBvhNode n{};
    quantize(children, k, n);
    // The traversal takes the nearest child next and leaves the others, leaves too, on its stack.
    std::uint32_t below = p.stack + std::uint32_t(k - 1);
    m.stack = std::max(m.stack, below);
    m.depth = std::max(m.depth, p.depth);
    glm::vec3 scale(scaleOf(n.scales & 0xffu), scaleOf((n.scales >> 8) & 0xffu), scaleOf((n.scales >> 16) & 0xffu));
    for (int i = 0; i < k; ++i) {
        const Child& c = children[i];
        std::uint32_t shift = 8u * std::uint32_t(i);
        glm::vec3 lo(decode(n.origin.x, (n.lowerX >> shift) & 0xffu, scale.x), decode(n.origin.y, (n.lowerY >> shift) & 0xffu, scale.y),
                     decode(n.origin.z, (n.lowerZ >> shift) & 0xffu, scale.z));
        glm::vec3 hi(decode(n.origin.x, (n.upperX >> shift) & 0xffu, scale.x), decode(n.origin.y, (n.upperY >> shift) & 0xffu, scale.y),
                     decode(n.origin.z, (n.upperZ >> shift) & 0xffu, scale.z));
        m.area += surface(lo, hi) * (c.count == 0 ? 1.0 : double(c.count));
        if (c.count == 0) {
            auto at = std::uint32_t(nodes.size());
            nodes.emplace_back();
            queue.push_back(Pending{c.index, at, below, p.depth + 1});
            n.children[i] = at;
            n.kinds |= WIDE_CHILD_INNER << shift;
        } else {
            if (c.count > BVH_LEAF_MAX || c.index > WIDE_LEAF_FIRST_MASK) {
                throw std::logic_error("a binary BVH leaf of " + std::to_string(c.count) + " primitives from reference " +
                                       std::to_string(c.index));
            }
            n.children[i] = c.index;
            n.kinds |= c.count << shift;
        }
    }
    nodes[p.wide] = n;
}

// Wide nodes left waiting by the top levels, each the root of a subtree of its own: enough for
// every thread, and fixed, so that the nodes' order does not depend on the thread count.
constexpr std::size_t kSubtrees = 1024;

}  // namespace

void widenBvh(const BinaryBvh& tree, std::vector<WideBvhNode>& wide, BvhStats& stats) {
    Clock::time_point start = Clock::now();
    stats.wideNodes = 0;
    stats.wideDepth = 0;
    stats.stack = 0;
    stats.wideSahCost = 0.0;
    if (tree.top.empty() && tree.subtrees.empty()) {
        wide.clear();
        stats.widenSeconds = std::chrono::duration<double>(Clock::now() - start).count();
        return;
    }
    // The top levels, breadth first, until enough nodes are waiting (a number fixed by the tree).
    BinaryReader binary{tree};
    WideMeasure top;
    std::vector<WideBvhNode> topNodes(1);
    std::vector<Pending> queue{Pending{0, 0, 0, 1}};
    std::size_t next = 0;
    while (next < queue.size() && queue.size() - next < kSubtrees) {
        makeNode(binary, queue[next], topNodes, queue, top);
        ++next;
    }
    // The waiting nodes' subtrees, each into its own array, then after the top in order.
    std::vector<Pending> roots(queue.begin() + std::ptrdiff_t(next), queue.end());
    std::vector<std::vector<WideBvhNode>> subtrees(roots.size());
    std::vector<WideMeasure> measures(roots.size());
    std::vector<std::uint32_t> offsets(roots.size());
    std::uint32_t count = std::uint32_t(topNodes.size());
    // A subtree's root takes the place that the top levels gave it; its descendants follow.
    parallelFor(roots.size(), 1, [&](std::size_t a, std::size_t b) {
        // Each subtree is made in `built`, whose memory the next reuses (warm, no page faults, no
        // growing), and kept in an array of its size.
        BinaryReader reader{tree};
        std::vector<Pending> local;
        std::vector<WideBvhNode> built;
        for (std::size_t r = a; r < b; ++r) {
            local.clear();
            local.push_back(Pending{roots[r].binary, 0, roots[r].stack, roots[r].depth});
            built.assign(1, WideBvhNode{});
            for (std::size_t i = 0; i < local.size(); ++i) {
                makeNode(reader, local[i], built, local, measures[r]);
            }
            subtrees[r].assign(built.begin(), built.end());
        }
    });
    for (std::size_t r = 0; r < roots.size(); ++r) {
        offsets[r] = count;
        count += std::uint32_t(subtrees[r].size()) - 1;
    }
    // `wide` may come sized already (buildBvh has a helper thread size it during the binary build).
    wide.resize(count);
    std::copy(topNodes.begin(), topNodes.end(), wide.begin());
    parallelFor(roots.size(), 1, [&](std::size_t a, std::size_t b) {
        for (std::size_t r = a; r < b; ++r) {
            // Node 0 of a subtree is its root (placed by the top levels), node i > 0 goes to
            // offsets[r] + i − 1; inner children's indices are moved to match.
            std::vector<WideBvhNode>& nodes = subtrees[r];
            for (std::size_t i = 0; i < nodes.size(); ++i) {
                WideBvhNode n = nodes[i];
                for (std::uint32_t c = 0; c < BVH_WIDTH; ++c) {
                    if (((n.kinds >> (8 * c)) & 0xffu) == WIDE_CHILD_INNER) {
                        n.children[c] = offsets[r] + n.children[c] - 1;
                    }
                }
                wide[i == 0 ? roots[r].wide : offsets[r] + i - 1] = n;
            }
            std::vector<WideBvhNode>().swap(nodes);
        }
    });
    // Statistics, summed in the tree's order.
    WideMeasure all = top;
    for (const WideMeasure& m : measures) {
        all.area += m.area;
        all.depth = std::max(all.depth, m.depth);
        all.stack = std::max(all.stack, m.stack);
    }
    Child rootChildren[2];
    int rootCount = binaryChildren(binary[0], rootChildren);
    glm::vec3 rootLower = rootChildren[0].lower;
    glm::vec3 rootUpper = rootChildren[0].upper;
    for (int i = 1; i < rootCount; ++i) {
        rootLower = glm::min(rootLower, rootChildren[i].lower);
        rootUpper = glm::max(rootUpper, rootChildren[i].upper);
    }
    double rootArea = std::max(surface(rootLower, rootUpper), 1e-30);
    stats.wideNodes = std::uint32_t(wide.size());
    stats.wideDepth = all.depth;
    stats.stack = all.stack;
    stats.wideSahCost = 1.0 + all.area / rootArea;
    stats.widenSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (stats.stack > BVH_STACK_SIZE) {
        throw InputError("the scene's bounding volume hierarchy could need " + std::to_string(stats.stack) +
                         " entries of its traversal's stack, more than its " + std::to_string(BVH_STACK_SIZE) +
                         " (many primitives in one place?)");
    }
}

BvhStats buildBvh(const Scene& scene, std::vector<WideBvhNode>& nodes, std::vector<std::uint32_t>& refs) {
    // The wide nodes are sized while the binary tree is built: the bench's meshes have a wide node
    // per 6.8 primitives, the estimate is a little more (widenBvh sizes them exactly). Address
    // space is reserved for half a node a primitive (untouched pages cost nothing), so that a
    // tree larger than the estimate is not moved.
    const std::size_t primitives = scene.spheres.size() + scene.quads.size() + scene.triangles.size();
    SizedOnHelper<WideBvhNode> sized(nodes, primitives / 2 + 64, primitives * 3 / 20);
    BinaryBvh binary;
    BvhStats stats = buildBinaryBvh(scene, binary, refs);
    widenBvh(binary, sized.get(), stats);
    stats.buildSeconds += stats.widenSeconds;
    return stats;
}

}  // namespace photon
