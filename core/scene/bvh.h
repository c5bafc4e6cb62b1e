// The bounding volume hierarchy over a scene's bounded primitives (spheres, quads, triangles;
// planes are infinite and stay apart), built on the host and traversed by shared/intersect.h on
// every backend. Built binary first: binned SAH (Wald, "On fast Construction of SAH-based
// Bounding Volume Hierarchies", 2007): at every node, primitives are binned by centroid into 8
// bins along each axis that may hold the split and split where the surface area heuristic is
// lowest; leaves hold at most 4 primitives. The top levels are split one level at a time on all
// threads, the subtrees below them each by one thread (core/scene/bvh.cpp says how), which also
// collapses its subtree into the four-wide, quantized nodes that the traversal reads (bvh_wide.cpp);
// the top levels are collapsed last. The result depends on the scene alone: the same nodes and
// references on any number of threads.
#pragma once

#include <cstdint>
#include <vector>

#include "shared/layout.h"

namespace photon {

struct Scene;

// A node of the binary hierarchy (the build's own, never kept: a subtree's until it is collapsed),
// with both children's boxes. A child is an inner node (count 0: `child` is its node) or a leaf
// (count primitives from the references' `child`); an absent child's box is a point at FLOAT_MAX.
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
    // threads); the subtrees below them, each built and collapsed into wide nodes (one thread
    // each); the top nodes' boxes and the binary tree measured; the top nodes collapsed into wide
    // ones and the subtrees' wide nodes placed after them.
    double prepareSeconds = 0.0;
    double topSeconds = 0.0;
    double subtreeSeconds = 0.0;  // the subtrees' wide collapse included
    double flattenSeconds = 0.0;
    double widenSeconds = 0.0;    // the top's collapse and the concatenation only
};

// The traversed hierarchy of the scene's spheres, quads and triangles: its wide nodes (the root
// first) and primitive references (kind << 30 | index); empty when there is no bounded primitive.
// A wide node takes the children of its binary node and replaces the largest inner one by its own
// two until it has four; boxes quantized outwards. Throws InputError if the traversal's stack
// (BVH_STACK_SIZE) could overflow.
BvhStats buildBvh(const Scene& scene, std::vector<WideBvhNode>& nodes, std::vector<std::uint32_t>& refs);

}  // namespace photon
