// Ray-primitive intersection and the two scene queries every stage needs, the closest hit and
// "is anything in the way", both through one traversal (traceRay).
#ifndef PHOTON_SHARED_INTERSECT_H
#define PHOTON_SHARED_INTERSECT_H

#include "bindings.h"
#include "math.h"

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

// Möller–Trumbore, two-sided.
PH_FN float intersectTriangle(PH_IN(Ray) ray, PH_IN(Triangle) tri, float tMax) {
    vec3 pvec = cross(ray.direction, tri.edge2);
    float det = dot(tri.edge1, pvec);
    if (abs(det) < 1.0e-20f) {
        return tMax;
    }
    float invDet = 1.0f / det;
    vec3 tvec = ray.origin - tri.v0;
    float u = dot(tvec, pvec) * invDet;
    if (u < 0.0f || u > 1.0f) {
        return tMax;
    }
    vec3 qvec = cross(tvec, tri.edge1);
    float v = dot(ray.direction, qvec) * invDet;
    if (v < 0.0f || u + v > 1.0f) {
        return tMax;
    }
    float t = dot(tri.edge2, qvec) * invDet;
    return (t > 0.0f && t < tMax) ? t : tMax;
}

PH_CONST uint QUERY_CLOSEST = 0u;  // the nearest surface along the ray
PH_CONST uint QUERY_ANY = 1u;      // whether there is any (shadow rays): the first one found will do

PH_FN uint primitiveCount(BUF_PARAM uint kind) {
    if (kind == PRIM_SPHERE) {
        return BUF(params).scene.sphereCount;
    }
    if (kind == PRIM_PLANE) {
        return BUF(params).scene.planeCount;
    }
    if (kind == PRIM_QUAD) {
        return BUF(params).scene.quadCount;
    }
    return BUF(params).scene.triangleCount;
}

// Where the ray meets primitive (kind, index) within (0, tMax), or tMax if it does not.
PH_FN float intersectPrimitive(BUF_PARAM uint kind, uint index, PH_IN(Ray) ray, float tMax) {
    if (kind == PRIM_SPHERE) {
        return intersectSphere(ray, BUF(spheres)[index].center, BUF(spheres)[index].radius, tMax);
    }
    if (kind == PRIM_PLANE) {
        return intersectPlane(ray, BUF(planes)[index].normal, BUF(planes)[index].offset, tMax);
    }
    if (kind == PRIM_QUAD) {
        return intersectQuad(ray, BUF(quads)[index], tMax);
    }
    return intersectTriangle(ray, BUF(triangles)[index], tMax);
}

// The one traversal of the scene: it visits the primitives the ray may meet and keeps the nearest
// hit within (0, ray.tMax) (QUERY_ANY: stops at the first). Today the candidates are every
// primitive, kind by kind; an acceleration structure replaces this loop and nothing else.
PH_FN bool traceRay(BUF_PARAM PH_IN(Ray) ray, uint query, PH_OUT(float) t, PH_OUT(uint) kind, PH_OUT(uint) index) {
    t = ray.tMax;
    kind = NONE;
    index = NONE;
    for (uint k = 0u; k < PRIM_KIND_COUNT; ++k) {
        uint count = primitiveCount(BUF_ARG k);
        for (uint i = 0u; i < count; ++i) {
            float tk = intersectPrimitive(BUF_ARG k, i, ray, t);
            if (tk < t) {
                t = tk;
                kind = k;
                index = i;
                if (query == QUERY_ANY) {
                    return true;
                }
            }
        }
    }
    return kind != NONE;
}

// The surface of primitive (kind, index) at a point on it: geometric normal and material.
PH_FN void primitiveSurface(BUF_PARAM uint kind, uint index, vec3 p, PH_OUT(vec3) normal, PH_OUT(uint) material) {
    if (kind == PRIM_SPHERE) {
        Sphere s = BUF(spheres)[index];
        normal = (p - s.center) * (1.0f / s.radius);
        material = s.material;
    } else if (kind == PRIM_PLANE) {
        normal = BUF(planes)[index].normal;
        material = BUF(planes)[index].material;
    } else if (kind == PRIM_QUAD) {
        normal = unitVector(BUF(quads)[index].w);
        material = BUF(quads)[index].material;
    } else {
        normal = unitVector(cross(BUF(triangles)[index].edge1, BUF(triangles)[index].edge2));
        material = BUF(triangles)[index].material;
    }
}

// Closest intersection along the ray within (0, ray.tMax).
PH_FN bool traceClosest(BUF_PARAM PH_IN(Ray) ray, PH_OUT(Hit) hit) {
    if (!traceRay(BUF_ARG ray, QUERY_CLOSEST, hit.t, hit.kind, hit.index)) {
        return false;
    }
    hit.position = ray.origin + hit.t * ray.direction;
    primitiveSurface(BUF_ARG hit.kind, hit.index, hit.position, hit.normal, hit.material);
    return true;
}

// Whether anything lies on the segment from origin along direction within (0, tMax).
PH_FN bool traceOccluded(BUF_PARAM vec3 origin, vec3 direction, float tMax) {
    float t;
    uint kind;
    uint index;
    return traceRay(BUF_ARG makeRay(origin, direction, tMax), QUERY_ANY, t, kind, index);
}

PH_NAMESPACE_END

#endif
