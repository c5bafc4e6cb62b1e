// The bounding volume hierarchy over a scene's bounded primitives (spheres, quads, triangles;
// planes are infinite and stay apart), built on the host and traversed by shared/intersect.h on
// every backend. Binned SAH (Wald, "On fast Construction of SAH-based Bounding Volume
// Hierarchies", 2007): at every node, primitives are binned by centroid into 8 bins along each
// axis that may hold the split and split where the surface area heuristic is lowest; leaves hold
// at most 4 primitives. The top levels are split one level at a time on all threads, the
// subtrees below them each by one thread (core/scene/bvh.cpp says how). The result depends on
// the scene alone: the same nodes and references on any number of threads.
#pragma once

#include <cstdint>
#include <vector>

#include "shared/layout.h"

namespace photon {

struct Scene;

struct BvhStats {
    std::uint32_t primitives = 0;  // bounded primitives in the hierarchy
    std::uint32_t nodes = 0;       // BvhNodes (each holds two children)
    std::uint32_t leaves = 0;
    std::uint32_t depth = 0;       // inner nodes on the longest path from the root
    double sahCost = 0.0;          // Σ area(inner)/area(root) + Σ area(leaf)/area(root)·primitives
    double buildSeconds = 0.0;
    // Where buildSeconds went: the primitives' centroids; the top levels (split across all
    // threads); the subtrees below them (one thread each); the nodes gathered into their array
    // and measured.
    double prepareSeconds = 0.0;
    double topSeconds = 0.0;
    double subtreeSeconds = 0.0;
    double flattenSeconds = 0.0;
};

// Builds the hierarchy of the scene's spheres, quads and triangles into `nodes` and `refs`
// (primitive references, kind << 30 | index). Empty outputs when there is no bounded primitive.
// Throws InputError if the hierarchy would be deeper than the traversal's stack (BVH_STACK_SIZE).
BvhStats buildBvh(const Scene& scene, std::vector<BvhNode>& nodes, std::vector<std::uint32_t>& refs);

}  // namespace photon
