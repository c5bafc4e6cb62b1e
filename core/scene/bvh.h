// The bounding volume hierarchy over a scene's bounded primitives (spheres, quads, triangles;
// planes are infinite and stay apart), built on the host and traversed by shared/intersect.h on
// every backend. Built binary first: binned SAH (Wald, "On fast Construction of SAH-based
// Bounding Volume Hierarchies", 2007): at every node, primitives are binned by centroid into 8
// bins along each axis that may hold the split and split where the surface area heuristic is
// lowest; leaves hold at most 4 primitives. The top levels are split one level at a time on all
// threads, the subtrees below them each by one thread (core/scene/bvh.cpp says how). Then
// collapsed into the four-wide, quantized nodes that the traversal reads (bvh_wide.cpp). The
// result depends on the scene alone: the same nodes and references on any number of threads.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "shared/layout.h"

namespace photon {

struct Scene;

// A node of the binary hierarchy, with both children's boxes. A child is an inner node (count 0:
// `child` is its node) or a leaf (count primitives from the references' `child`); an absent child's
// box is a point at FLOAT_MAX.
struct BvhNode {
    glm::vec3 lowerA; std::uint32_t childA;
    glm::vec3 upperA; std::uint32_t countA;
    glm::vec3 lowerB; std::uint32_t childB;
    glm::vec3 upperB; std::uint32_t countB;
};

struct BvhStats {
    std::uint32_t primitives = 0;  // bounded primitives in the hierarchy
    std::uint32_t nodes = 0;       // binary nodes (each holds two children)
    std::uint32_t leaves = 0;
    std::uint32_t depth = 0;       // binary inner nodes on the longest path from the root
    double sahCost = 0.0;          // of the binary tree: Σ area(inner)/area(root) + Σ area(leaf)/area(root)·primitives
    std::uint32_t wideNodes = 0;   // WideBvhNodes (each holds four children)
    std::uint32_t wideDepth = 0;   // wide inner nodes on the longest path from the root
    std::uint32_t stack = 0;       // the most entries the wide traversal's stack can hold at once
    double wideSahCost = 0.0;      // of the wide tree, over its quantized boxes
    double buildSeconds = 0.0;
    // Where buildSeconds went: the primitives' centroids; the top levels (split across all
    // threads); the subtrees below them (one thread each); the top nodes' boxes and the tree
    // measured; the binary tree collapsed into the wide one.
    double prepareSeconds = 0.0;
    double topSeconds = 0.0;
    double subtreeSeconds = 0.0;
    double flattenSeconds = 0.0;
    double widenSeconds = 0.0;
};

// The binary hierarchy as its build leaves it, never copied into one array: the top levels' nodes,
// then each subtree's own nodes, whose inner children are numbered from the subtree's first node.
// Node g of the whole is top[g], or node g − offsets[k] of the last subtree k with offsets[k] ≤ g,
// its inner children moved by offsets[k] (what one array would hold; the collapse reads it so).
struct BinaryBvh {
    std::vector<BvhNode> top;
    std::vector<std::vector<BvhNode>> subtrees;
    std::vector<std::uint32_t> offsets;  // each subtree's first node in the whole

    // Node g of the whole; `hint` is the subtree read last, searched for again only when g is
    // outside it (the collapse reads a subtree's nodes together).
    BvhNode node(std::uint32_t g, std::size_t& hint) const {
        if (g < top.size()) {
            return top[g];
        }
        if (hint >= offsets.size() || g < offsets[hint] || g - offsets[hint] >= subtrees[hint].size()) {
            hint = std::size_t(std::upper_bound(offsets.begin(), offsets.end(), g) - offsets.begin()) - 1;
        }
        const std::uint32_t offset = offsets[hint];
        BvhNode n = subtrees[hint][g - offset];
        n.childA += n.countA == 0 && n.lowerA.x != FLOAT_MAX ? offset : 0;
        n.childB += n.countB == 0 && n.lowerB.x != FLOAT_MAX ? offset : 0;
        return n;
    }
};

// The binary hierarchy of the scene's spheres, quads and triangles into `binary` and `refs`
// (primitive references, kind << 30 | index). Empty outputs when there is no bounded primitive.
BvhStats buildBinaryBvh(const Scene& scene, BinaryBvh& binary, std::vector<std::uint32_t>& refs);

// The binary hierarchy collapsed into wide nodes (the root first), each taking the children of
// its binary node and replacing the largest inner one by its own two until it has four; boxes
// quantized outwards. Sets the wide fields of `stats`. Throws InputError if the traversal's
// stack (BVH_STACK_SIZE) could overflow.
void widenBvh(const BinaryBvh& binary, std::vector<WideBvhNode>& wide, BvhStats& stats);

// The traversed hierarchy: buildBinaryBvh, then widenBvh.
BvhStats buildBvh(const Scene& scene, std::vector<WideBvhNode>& nodes, std::vector<std::uint32_t>& refs);

}  // namespace photon
