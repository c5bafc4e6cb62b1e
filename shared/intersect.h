// Ray-primitive intersection and the two scene queries every stage needs, the closest hit and
// "is anything in the way", both through one traversal (traceRay): infinite planes tested one by
// one, every bounded primitive (sphere, quad, triangle) through a bounding volume hierarchy built on
// the host (core/scene/bvh.cpp).
#ifndef PHOTON_SHARED_INTERSECT_H
#define PHOTON_SHARED_INTERSECT_H

#include "bindings.h"
#include "math.h"
#include "texture.h"
// The CPU build for x86-64 tests a wide node's four boxes at once with SSE2 (PH_WIDE_BOX_SIMD);
// for nvcc and glslang the header is empty and traceRay's loop tests them one by one.
#include "wide_box_test_simd.h"

PH_NAMESPACE_BEGIN

struct Ray {
    vec3 origin;
    vec3 direction;  // unit length
    float tMax;
};

struct Hit {
    vec3 position;
    float t;
    vec3 normal;  // geometric, unit; outward for spheres, the primitive's own side otherwise
    uint material;
    uint kind;    // PRIM_*
    uint index;
    float b1;     // triangles: barycentric weights of v1 and v2 at the hit
    float b2;
};

PH_FN Ray makeRay(vec3 origin, vec3 direction, float tMax) {
    Ray r;
    r.origin = origin;
    r.direction = direction;
    r.tMax = tMax;
    return r;
}

// Sphere: the numerically careful form of "Precision Improvements for Ray/Sphere Intersection"
// (Haines et al., Ray Tracing Gems 2019): the discriminant from the perpendicular offset, the
// nearer root from c/q. Returns the nearest t in (0, tMax), or tMax if none.
PH_FN float intersectSphere(PH_IN(Ray) ray, vec3 center, float radius, float tMax) {
    vec3 f = ray.origin - center;
    float b = -dot(f, ray.direction);
    vec3 perpendicular = f + b * ray.direction;
    float r2 = radius * radius;
    float discriminant = r2 - dot(perpendicular, perpendicular);
    if (discriminant < 0.0f) {
        return tMax;
    }
    float q = b + signNotZero(b) * sqrt(discriminant);
    if (q == 0.0f) {
        return tMax;
    }
    float c = dot(f, f) - r2;
    float t0 = c / q;
    float t1 = q;
    float tNear = min(t0, t1);
    float tFar = max(t0, t1);
    if (tNear > 0.0f && tNear < tMax) {
        return tNear;
    }
    if (tFar > 0.0f && tFar < tMax) {
        return tFar;
    }
    return tMax;
}

PH_FN float intersectPlane(PH_IN(Ray) ray, vec3 normal, float offset, float tMax) {
    float denom = dot(normal, ray.direction);
    if (abs(denom) < 1.0e-12f) {
        return tMax;
    }
    float t = (offset - dot(normal, ray.origin)) / denom;
    return (t > 0.0f && t < tMax) ? t : tMax;
}

// Parallelogram corner + a·u + b·v: (a, b) from w = (u × v)/|u × v|² (Shirley, RTiOW: The Next Week).
PH_FN float intersectQuad(PH_IN(Ray) ray, PH_IN(Quad) quad, float tMax) {
    float denom = dot(quad.w, ray.direction);
    if (abs(denom) < 1.0e-20f) {
        return tMax;
    }
    float t = dot(quad.w, quad.corner - ray.origin) / denom;
    if (!(t > 0.0f && t < tMax)) {
        return tMax;
    }
    vec3 p = ray.origin + t * ray.direction - quad.corner;
    float a = dot(quad.w, cross(p, quad.edgeV));
    float b = dot(quad.w, cross(quad.edgeU, p));
    return (a >= 0.0f && a <= 1.0f && b >= 0.0f && b <= 1.0f) ? t : tMax;
}

// What every triangle test of a ray shares (Woop, Benthin and Wald, "Watertight Ray/Triangle
// Intersection", JCGT 2013): the axes permuted so that z is the direction's largest, and the shear
// that maps the ray onto +z. Also the inverse direction for box tests, with no zero component, so
// that no 0·∞ can arise.
struct RayFrame {
    vec3 origin;
    vec3 inverseDirection;
    uint kx;
    uint ky;
    uint kz;
    vec3 shear;  // (Sx, Sy, Sz)
};

PH_FN RayFrame makeRayFrame(PH_IN(Ray) ray) {
    RayFrame f;
    f.origin = ray.origin;
    vec3 d = ray.direction;
    vec3 a = abs(d);
    f.kz = a.x > a.y ? (a.x > a.z ? 0u : 2u) : (a.y > a.z ? 1u : 2u);
    f.kx = f.kz == 2u ? 0u : f.kz + 1u;
    f.ky = f.kx == 2u ? 0u : f.kx + 1u;
    if (d[f.kz] < 0.0f) {  // keep the winding: swap x and y
        uint k = f.kx;
        f.kx = f.ky;
        f.ky = k;
    }
    f.shear = vec3(d[f.kx] / d[f.kz], d[f.ky] / d[f.kz], 1.0f / d[f.kz]);
    vec3 safe = vec3(abs(d.x) < 1.0e-20f ? (d.x < 0.0f ? -1.0e-20f : 1.0e-20f) : d.x,
                     abs(d.y) < 1.0e-20f ? (d.y < 0.0f ? -1.0e-20f : 1.0e-20f) : d.y,
                     abs(d.z) < 1.0e-20f ? (d.z < 0.0f ? -1.0e-20f : 1.0e-20f) : d.z);
    f.inverseDirection = vec3(1.0f) / safe;
    return f;
}

// The watertight test: two-sided, no gaps along shared edges (an edge hit belongs to both
// triangles). Returns t in (0, tMax) or tMax; b1, b2 are the barycentric weights of v1 and v2.
PH_FN float intersectTriangle(PH_IN(RayFrame) f, PH_IN(Triangle) tri, float tMax, PH_OUT(float) b1, PH_OUT(float) b2) {
    b1 = 0.0f;
    b2 = 0.0f;
    vec3 a = tri.v0 - f.origin;
    vec3 b = tri.v1 - f.origin;
    vec3 c = tri.v2 - f.origin;
    float ax = a[f.kx] - f.shear.x * a[f.kz];
    float ay = a[f.ky] - f.shear.y * a[f.kz];
    float bx = b[f.kx] - f.shear.x * b[f.kz];
    float by = b[f.ky] - f.shear.y * b[f.kz];
    float cx = c[f.kx] - f.shear.x * c[f.kz];
    float cy = c[f.ky] - f.shear.y * c[f.kz];
    float u = cx * by - cy * bx;
    float v = ax * cy - ay * cx;
    float w = bx * ay - by * ax;
    if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) {
        return tMax;
    }
    float det = u + v + w;
    if (det == 0.0f) {
        return tMax;
    }
    float az = f.shear.z * a[f.kz];
    float bz = f.shear.z * b[f.kz];
    float cz = f.shear.z * c[f.kz];
    float t = (u * az + v * bz + w * cz) / det;
    if (!(t > 0.0f && t < tMax)) {
        return tMax;
    }
    b1 = v / det;
    b2 = w / det;
    return t;
}

// Slab test of the box [lower, upper] within (0, tMax): the entry distance, or FLOAT_MAX if the
// ray misses it. An empty box (lower > upper) is always missed.
PH_FN float intersectBox(PH_IN(RayFrame) f, vec3 lower, vec3 upper, float tMax) {
    vec3 t0 = (lower - f.origin) * f.inverseDirection;
    vec3 t1 = (upper - f.origin) * f.inverseDirection;
    vec3 near = min(t0, t1);
    vec3 far = max(t0, t1);
    float enter = max(max(near.x, near.y), max(near.z, 0.0f));
    float leave = min(min(far.x, far.y), min(far.z, tMax));
    return enter <= leave ? enter : FLOAT_MAX;
}

PH_CONST uint QUERY_CLOSEST = 0u;  // the nearest surface along the ray
PH_CONST uint QUERY_ANY = 1u;      // whether there is any (shadow rays): the first one found will do

// A primitive reference of primitiveRefs: kind in the top 2 bits, index below.
PH_CONST uint PRIMITIVE_INDEX_BITS = 30u;
#ifdef __cplusplus
static_assert(PRIM_KIND_COUNT <= (1u << (32u - PRIMITIVE_INDEX_BITS)), "every PRIM_* fits a reference's kind bits");
#endif
PH_FN uint primitiveKind(uint ref) { return ref >> PRIMITIVE_INDEX_BITS; }
PH_FN uint primitiveIndex(uint ref) { return ref & ((1u << PRIMITIVE_INDEX_BITS) - 1u); }

// Where the ray meets bounded primitive `ref` within (0, tMax), or tMax if it does not.
PH_FN float intersectPrimitive(BUF_PARAM uint ref, PH_IN(Ray) ray, PH_IN(RayFrame) frame, float tMax, PH_OUT(float) b1,
                               PH_OUT(float) b2) {
    uint kind = primitiveKind(ref);
    uint index = primitiveIndex(ref);
    b1 = 0.0f;
    b2 = 0.0f;
    PH_COVERS(PRIM_KIND_COUNT, 4u);
    switch (kind) {
        case PRIM_SPHERE:
            return intersectSphere(ray, BUF(spheres)[index].center, BUF(spheres)[index].radius, tMax);
        case PRIM_QUAD:
            return intersectQuad(ray, BUF(quads)[index], tMax);
        case PRIM_TRIANGLE: {
            Triangle tri = BUF(triangles)[index];
            float t = intersectTriangle(frame, tri, tMax, b1, b2);
            if (t < tMax && tri.flags != 0u) {
                if ((tri.flags & TRIANGLE_BACK_CULLED) != 0u && dot(ray.direction, cross(tri.v1 - tri.v0, tri.v2 - tri.v0)) > 0.0f) {
                    return tMax;  // its back, which a single-sided surface does not have
                }
                if ((tri.flags & TRIANGLE_ALPHA_TESTED) != 0u && !coverageHolds(BUF_ARG tri, b1, b2, ray.direction)) {
                    return tMax;  // cut out (alpha mask) or, this time, seen through (alpha blend)
                }
            }
            return t;
        }
        case PRIM_PLANE:
            break;  // unbounded: traceRay tests planes apart, the host never references one (bvh.cpp)
    }
    return tMax;
}

// The result of a scene query.
struct TraceResult {
    float t;
    uint kind;   // PRIM_*, NONE: nothing within tMax
    uint index;
    float b1;    // barycentric weights of a triangle hit
    float b2;
};

// Tests the primitives of a leaf, keeping the nearest hit. True when a QUERY_ANY is answered.
PH_FN bool traceLeaf(BUF_PARAM uint first, uint count, PH_IN(Ray) ray, PH_IN(RayFrame) frame, uint query,
                     PH_INOUT(TraceResult) result) {
    for (uint i = first; i < first + count; ++i) {
        uint ref = BUF(primitiveRefs)[i];
        float b1;
        float b2;
        float t = intersectPrimitive(BUF_ARG ref, ray, frame, result.t, b1, b2);
        if (t < result.t) {
            result.t = t;
            result.kind = primitiveKind(ref);
            result.index = primitiveIndex(ref);
            result.b1 = b1;
            result.b2 = b2;
            if (query == QUERY_ANY) {
                return true;
            }
        }
    }
    return false;
}

// Child i's box of wide node n (layout.h: origin + q · scale per axis) against the ray.
PH_FN float wideChildEntry(PH_IN(RayFrame) f, PH_IN(WideBvhNode) n, vec3 scale, uint i, float tMax) {
    uint shift = 8u * i;
    vec3 lower = vec3(float((n.lowerX >> shift) & 0xffu), float((n.lowerY >> shift) & 0xffu), float((n.lowerZ >> shift) & 0xffu));
    vec3 upper = vec3(float((n.upperX >> shift) & 0xffu), float((n.upperY >> shift) & 0xffu), float((n.upperZ >> shift) & 0xffu));
    return intersectBox(f, n.origin + lower * scale, n.origin + upper * scale, tMax);
}

// A wide node's quantization steps 2^(e − 127), e the bytes of `scales`.
PH_FN vec3 wideScale(uint scales) {
    return vec3(uintBitsToFloat((scales & 0xffu) << 23u), uintBitsToFloat(((scales >> 8u) & 0xffu) << 23u),
                uintBitsToFloat(((scales >> 16u) & 0xffu) << 23u));
}

// What the traversal keeps of a child, in one word: an inner node's index, or a leaf's first
// primitive reference and count with WIDE_LEAF_CODE set.
PH_FN uint wideChildCode(uint child, uint kind) {
    return kind == WIDE_CHILD_INNER ? child : WIDE_LEAF_CODE | ((kind - 1u) << WIDE_LEAF_COUNT_SHIFT) | child;
}

// Orders two children (entry, code) by entry, the nearer first; equal entries keep their order.
PH_FN void orderChildren(PH_INOUT(float) entryA, PH_INOUT(uint) codeA, PH_INOUT(float) entryB, PH_INOUT(uint) codeB) {
    if (entryB < entryA) {
        float e = entryA;
        entryA = entryB;
        entryB = e;
        uint c = codeA;
        codeA = codeB;
        codeB = c;
    }
}

// A wide node's children that the ray enters within tMax, nearest first: their entry distances
// (FLOAT_MAX: missed, or no child) and codes (wideChildCode). Equal entries keep their order.
PH_FN void wideNodeChildren(BUF_PARAM uint node, PH_IN(RayFrame) frame, float tMax, PH_OUT(vec4) entry, PH_OUT(uvec4) code) {
    WideBvhNode n = BUF(bvhNodes)[node];
    vec3 scale = wideScale(n.scales);
#ifdef PH_WIDE_BOX_SIMD
    vec4 e = wideChildEntriesSimd(n, frame.origin, frame.inverseDirection, scale, tMax);
#else
    vec4 e = vec4(FLOAT_MAX);
    for (uint i = 0u; i < BVH_WIDTH; ++i) {
        if (((n.kinds >> (8u * i)) & 0xffu) == WIDE_CHILD_EMPTY) {
            break;
        }
        e[i] = wideChildEntry(frame, n, scale, i, tMax);
    }
#endif
    float e0 = e.x;
    float e1 = e.y;
    float e2 = e.z;
    float e3 = e.w;
    uint c0 = wideChildCode(n.children.x, n.kinds & 0xffu);
    uint c1 = wideChildCode(n.children.y, (n.kinds >> 8u) & 0xffu);
    uint c2 = wideChildCode(n.children.z, (n.kinds >> 16u) & 0xffu);
    uint c3 = wideChildCode(n.children.w, n.kinds >> 24u);
    orderChildren(e0, c0, e1, c1);
    orderChildren(e2, c2, e3, c3);
    orderChildren(e0, c0, e2, c2);
    orderChildren(e1, c1, e3, c3);
    orderChildren(e1, c1, e2, c2);
    entry = vec4(e0, e1, e2, e3);
    code = uvec4(c0, c1, c2, c3);
}

// The four-wide hierarchy's part of traceRay, in one loop over inner nodes and leaves alike, in
// the manner of Aila and Laine ("Understanding the Efficiency of Ray Traversal on GPUs", HPG 2009)
// and Ylitie et al. (HPG 2017): a node's children are sorted by where the ray enters their boxes;
// the nearest is taken next, the others go on a stack with their entry distances, nearest on top,
// and are skipped when they come off it if a hit nearer than their box has been found meanwhile.
// Leaves go through the stack like inner nodes (one place tests them, not one per child: the
// primitive tests are large). The host builds no hierarchy that needs more than BVH_STACK_SIZE.
// Every backend walks the nodes in the same order, so that ties between equally near primitives
// break alike. True when a QUERY_ANY is answered.
PH_FN bool traceWide(BUF_PARAM PH_IN(Ray) ray, PH_IN(RayFrame) frame, uint query, PH_INOUT(TraceResult) result) {
    // A waiting child's code and entry distance side by side: one 8-byte access where a GPU keeps
    // the stack in local memory.
    uvec2 stack[BVH_STACK_SIZE];
    uint depth = 0u;
    uint code = 0u;  // the root
    while (true) {
        if ((code & WIDE_LEAF_CODE) != 0u) {
            uint count = ((code >> WIDE_LEAF_COUNT_SHIFT) & 3u) + 1u;
            if (traceLeaf(BUF_ARG code & WIDE_LEAF_FIRST_MASK, count, ray, frame, query, result)) {
                return true;
            }
        } else {
            vec4 e;
            uvec4 c;
            wideNodeChildren(BUF_ARG code, frame, result.t, e, c);
            if (e.w < FLOAT_MAX) {
                stack[depth] = uvec2(c.w, floatBitsToUint(e.w));
                depth += 1u;
            }
            if (e.z < FLOAT_MAX) {
                stack[depth] = uvec2(c.z, floatBitsToUint(e.z));
                depth += 1u;
            }
            if (e.y < FLOAT_MAX) {
                stack[depth] = uvec2(c.y, floatBitsToUint(e.y));
                depth += 1u;
            }
            if (e.x < FLOAT_MAX) {
                code = c.x;
                continue;
            }
        }
        // The nearest waiting child that a hit found since has not put out of reach.
        bool next = false;
        while (depth > 0u && !next) {
            depth -= 1u;
            uvec2 waiting = stack[depth];
            code = waiting.x;
            next = uintBitsToFloat(waiting.y) < result.t;
        }
        if (!next) {
            return false;
        }
    }
    return false;
}

#ifdef __cplusplus
// traceWide for the lanes of a warp (Aila and Laine's "while-while" with speculative traversal):
// inner nodes and leaves in loops of their own, and a lane that meets a leaf sets it aside and
// goes on down the inner nodes until every lane of its warp holds one, so that the warp's lanes
// test their leaves together instead of one lane's leaf at a time while the others wait. Leaves
// are still tested in the order they are met, and a node that a hit has put out of reach since it
// was met is skipped, so the hit is traceWide's: going on speculatively costs only the nodes
// visited in vain. A lane alone (PH_ANY_LANE on the CPU, where the tests run it) tests its leaf
// at once, and walks traceWide's nodes.
//
// CUDA traces with it (PH_SPECULATIVE_TRAVERSAL: its eye pass 5-15% faster on meshes, primary rays
// 17-20%). GLSL has it not: NVIDIA's Vulkan driver ran the nested loops 1.5-2.6x slower without
// the vote and 1.3-3.4x slower with it (subgroupAny; docs/performance.md, sessions 12 and 13).
PH_FN bool traceWideSpeculative(BUF_PARAM PH_IN(Ray) ray, PH_IN(RayFrame) frame, uint query, PH_INOUT(TraceResult) result) {
    uvec2 stack[BVH_STACK_SIZE];
    uint depth = 0u;
    uint code = 0u;      // the next node, the root first
    float entry = 0.0f;  // where the ray enters it
    bool more = true;    // whether there is a next node
    uint leaf = 0u;      // a leaf set aside (0: none; a leaf's code is never 0)
    while (more || leaf != 0u) {
        while (more) {
            bool pop = !(entry < result.t);
            if (!pop && (code & WIDE_LEAF_CODE) != 0u) {
                if (leaf != 0u) {
                    break;  // a second leaf: test the first
                }
                leaf = code;
                pop = true;
            } else if (!pop) {
                vec4 e;
                uvec4 c;
                wideNodeChildren(BUF_ARG code, frame, result.t, e, c);
                if (e.w < FLOAT_MAX) {
                    stack[depth] = uvec2(c.w, floatBitsToUint(e.w));
                    depth += 1u;
                }
                if (e.z < FLOAT_MAX) {
                    stack[depth] = uvec2(c.z, floatBitsToUint(e.z));
                    depth += 1u;
                }
                if (e.y < FLOAT_MAX) {
                    stack[depth] = uvec2(c.y, floatBitsToUint(e.y));
                    depth += 1u;
                }
                code = c.x;
                entry = e.x;
                pop = !(e.x < FLOAT_MAX);
            }
            if (pop) {
                more = false;
                while (depth > 0u && !more) {
                    depth -= 1u;
                    uvec2 waiting = stack[depth];
                    code = waiting.x;
                    entry = uintBitsToFloat(waiting.y);
                    more = entry < result.t;
                }
            }
            if (!PH_ANY_LANE(leaf == 0u)) {
                break;  // every lane holds a leaf
            }
        }
        if (leaf != 0u) {
            uint count = ((leaf >> WIDE_LEAF_COUNT_SHIFT) & 3u) + 1u;
            if (traceLeaf(BUF_ARG leaf & WIDE_LEAF_FIRST_MASK, count, ray, frame, query, result)) {
                return true;
            }
            leaf = 0u;
        }
    }
    return false;
}
#endif

// The one traversal of the scene: the nearest hit within (0, ray.tMax) (QUERY_ANY: the first one
// found). Planes one by one, then the four-wide hierarchy.
PH_FN TraceResult traceRay(BUF_PARAM PH_IN(Ray) ray, uint query) {
    TraceResult result;
    result.t = ray.tMax;
    result.kind = NONE;
    result.index = NONE;
    result.b1 = 0.0f;
    result.b2 = 0.0f;
    for (uint i = 0u; i < BUF(params).scene.planeCount; ++i) {
        float t = intersectPlane(ray, BUF(planes)[i].normal, BUF(planes)[i].offset, result.t);
        if (t < result.t) {
            result.t = t;
            result.kind = PRIM_PLANE;
            result.index = i;
            if (query == QUERY_ANY) {
                return result;
            }
        }
    }
    RayFrame frame = makeRayFrame(ray);
    if (BUF(params).scene.bvhNodeCount == 0u) {
        traceLeaf(BUF_ARG 0u, BUF(params).scene.linearCount, ray, frame, query, result);
        return result;
    }
#ifdef PH_SPECULATIVE_TRAVERSAL
    traceWideSpeculative(BUF_ARG ray, frame, query, result);
#else
    traceWide(BUF_ARG ray, frame, query, result);
#endif
    return result;
}

// The surface of primitive (kind, index) at a point on it: geometric normal and material.
PH_FN void primitiveSurface(BUF_PARAM uint kind, uint index, vec3 p, PH_OUT(vec3) normal, PH_OUT(uint) material) {
    normal = vec3(0.0f, 0.0f, 1.0f);
    material = NONE;
    PH_COVERS(PRIM_KIND_COUNT, 4u);
    switch (kind) {
        case PRIM_SPHERE: {
            Sphere s = BUF(spheres)[index];
            normal = (p - s.center) * (1.0f / s.radius);
            material = s.material;
            break;
        }
        case PRIM_PLANE:
            normal = BUF(planes)[index].normal;
            material = BUF(planes)[index].material;
            break;
        case PRIM_QUAD:
            normal = unitVector(BUF(quads)[index].w);
            material = BUF(quads)[index].material;
            break;
        case PRIM_TRIANGLE: {
            Triangle tri = BUF(triangles)[index];
            normal = unitVector(cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
            material = tri.material;
            break;
        }
    }
}

// Closest intersection along the ray within (0, ray.tMax).
PH_FN bool traceClosest(BUF_PARAM PH_IN(Ray) ray, PH_OUT(Hit) hit) {
    TraceResult r = traceRay(BUF_ARG ray, QUERY_CLOSEST);
    if (r.kind == NONE) {
        return false;
    }
    hit.t = r.t;
    hit.kind = r.kind;
    hit.index = r.index;
    hit.b1 = r.b1;
    hit.b2 = r.b2;
    hit.position = ray.origin + r.t * ray.direction;
    // A surface so far away that the point on it overflows the float range (a plane through
    // 1e38, seen through a mirror) is out of reach: the ray has left the scene.
    if (!(abs(hit.position.x) <= FLOAT_MAX && abs(hit.position.y) <= FLOAT_MAX && abs(hit.position.z) <= FLOAT_MAX)) {
        return false;
    }
    primitiveSurface(BUF_ARG hit.kind, hit.index, hit.position, hit.normal, hit.material);
    return true;
}

// Whether anything lies on the segment from origin along direction within (0, tMax).
PH_FN bool traceOccluded(BUF_PARAM vec3 origin, vec3 direction, float tMax) {
    return traceRay(BUF_ARG makeRay(origin, direction, tMax), QUERY_ANY).kind != NONE;
}

PH_NAMESPACE_END

#endif
