// What the BVH build's phases (core/scene/bvh.cpp) share: the primitives they work from, the
// sums the SAH cost is measured from, and the parts of the tree that one phase hands the next
// (the top levels' nodes and the subtrees below them).
#pragma once

#include <memory>
#include <vector>

#include "core/scene/bvh_bins.h"
#include "core/scene/scene.h"

namespace photon::bvh_build {

// What the SAH cost, leaves and depth are summed from, per part of the tree (in an order fixed
// by the tree, so that the sums come out the same every time).
struct Measure {
    double area = 0.0;  // Σ over children: area × (primitives of a leaf, or kTraversalCost)
    std::uint32_t leaves = 0;
    std::uint32_t depth = 0;
};

// Writes a child into its parent's slot: a leaf (references first .. first + count) or inner node
// `index`; counts it in `m`.
inline void fill(BvhNode& parent, bool second, const Box& box, std::uint32_t first, std::uint32_t count,
          std::uint32_t index, bool leaf, Measure& m) {
    glm::vec3 lo = box.lower();
    glm::vec3 hi = box.upper();
    (second ? parent.lowerB : parent.lowerA) = lo;
    (second ? parent.upperB : parent.upperA) = hi;
    (second ? parent.childB : parent.childA) = leaf ? first : index;
    (second ? parent.countB : parent.countA) = leaf ? count : 0;
    m.area += area(lo, hi) * (leaf ? double(count) : double(kTraversalCost));
    m.leaves += leaf ? 1 : 0;
}

// The primitives' reference (kind << 30 | index) from their place in the box array, which holds
// the spheres, then the quads, then the triangles.
struct RefMap {
    std::uint32_t quads;      // first quad
    std::uint32_t triangles;  // first triangle
    std::uint32_t operator()(std::uint32_t i) const {
        if (i >= triangles) {
            return (PRIM_TRIANGLE << PRIMITIVE_INDEX_BITS) | (i - triangles);
        }
        return i >= quads ? (PRIM_QUAD << PRIMITIVE_INDEX_BITS) | (i - quads) : (PRIM_SPHERE << PRIMITIVE_INDEX_BITS) | i;
    }
};

// What the build works from: the scene's bounded primitives, whose boxes are computed where
// they are needed (never stored: 32 bytes a primitive, written and read once more than they
// save), their doubled centroids per axis, and the index array the hierarchy partitions.
struct Primitives {
    const Scene& scene;
    RefMap refMap;
    std::unique_ptr<float[]> centroid[3];
    std::unique_ptr<std::uint32_t[]> index;

    // The box of primitive i (the spheres, then the quads, then the triangles); fourth lanes 0.
    void box(std::uint32_t i, __m128& lo, __m128& hi) const {
        const __m128 xyz = _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1));
        if (i >= refMap.triangles) {
            const Triangle& t = scene.triangles[i - refMap.triangles];
            __m128 v0 = _mm_load_ps(&t.v0.x);
            __m128 v1 = _mm_load_ps(&t.v1.x);
            __m128 v2 = _mm_load_ps(&t.v2.x);
            lo = _mm_and_ps(_mm_min_ps(v0, _mm_min_ps(v1, v2)), xyz);
            hi = _mm_and_ps(_mm_max_ps(v0, _mm_max_ps(v1, v2)), xyz);
        } else if (i >= refMap.quads) {
            const Quad& q = scene.quads[i - refMap.quads];
            glm::vec3 corners[4] = {q.corner, q.corner + q.edgeU, q.corner + q.edgeV, q.corner + q.edgeU + q.edgeV};
            glm::vec3 l = corners[0];
            glm::vec3 h = corners[0];
            for (glm::vec3 k : corners) {
                l = glm::min(l, k);
                h = glm::max(h, k);
            }
            lo = _mm_setr_ps(l.x, l.y, l.z, 0.0f);
            hi = _mm_setr_ps(h.x, h.y, h.z, 0.0f);
        } else {
            const Sphere& s = scene.spheres[i];
            glm::vec3 l = s.center - glm::vec3(s.radius);
            glm::vec3 h = s.center + glm::vec3(s.radius);
            lo = _mm_setr_ps(l.x, l.y, l.z, 0.0f);
            hi = _mm_setr_ps(h.x, h.y, h.z, 0.0f);
        }
    }
    PrimBox box(std::uint32_t i) const {
        PrimBox b;
        __m128 lo;
        __m128 hi;
        box(i, lo, hi);
        _mm_store_ps(b.lo, lo);
        _mm_store_ps(b.hi, hi);
        return b;
    }
};

// A subtree: where its root goes, its primitives and box, and its nodes (indexed from 0, moved
// into the whole at the end; none when the root is a leaf).
struct Subtree {
    Slot slot;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    std::uint32_t depth = 1;
    Box box;  // measured by its build
    std::vector<BvhNode> nodes;
    Measure measure;
};

// A node of the top levels: where it goes and what its children are (a top node or a subtree).
struct TopNode {
    std::uint32_t child[2];
    bool subtree[2];
};

// Phase 2, the top levels (bvh_top_levels.cpp): splits the primitives from the root down, a level
// at a time on all threads, until every node is a subtree's size; returns the subtrees in the order
// they were made. Top node k is node k of the hierarchy. `scratch` (count entries; the reference
// array, which the subtrees fill later) holds each level's partitions on their way.
std::vector<Subtree> buildTopLevels(const Primitives& p, std::uint32_t count, std::uint32_t* scratch,
                                   std::vector<TopNode>& nodes);

// Phase 3, the subtrees (bvh_subtrees.cpp): builds each subtree whole on one thread, largest
// first, into its own nodes; leaves' references into `refs`.
void buildSubtrees(const Primitives& p, std::uint32_t* refs, std::vector<Subtree>& subtrees);

}  // namespace photon::bvh_build
