// Ray-primitive intersection and the two scene queries every stage needs: the closest hit and
// "is anything in the way". The scene is a handful of analytic primitives, tested linearly.
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

// Closest intersection along the ray within (0, ray.tMax).
PH_FN bool traceClosest(BUF_PARAM PH_IN(Ray) ray, PH_OUT(Hit) hit) {
    float tBest = ray.tMax;
    uint kind = NONE;
    uint index = NONE;
    for (uint i = 0u; i < BUF(params).scene.sphereCount; ++i) {
        float t = intersectSphere(ray, BUF(spheres)[i].center, BUF(spheres)[i].radius, tBest);
        if (t < tBest) {
            tBest = t;
            kind = PRIM_SPHERE;
            index = i;
        }
    }
    for (uint i = 0u; i < BUF(params).scene.planeCount; ++i) {
        float t = intersectPlane(ray, BUF(planes)[i].normal, BUF(planes)[i].offset, tBest);
        if (t < tBest) {
            tBest = t;
            kind = PRIM_PLANE;
            index = i;
        }
    }
    for (uint i = 0u; i < BUF(params).scene.quadCount; ++i) {
        float t = intersectQuad(ray, BUF(quads)[i], tBest);
        if (t < tBest) {
            tBest = t;
            kind = PRIM_QUAD;
            index = i;
        }
    }
    for (uint i = 0u; i < BUF(params).scene.triangleCount; ++i) {
        float t = intersectTriangle(ray, BUF(triangles)[i], tBest);
        if (t < tBest) {
            tBest = t;
            kind = PRIM_TRIANGLE;
            index = i;
        }
    }
    if (kind == NONE) {
        return false;
    }
    hit.t = tBest;
    hit.kind = kind;
    hit.index = index;
    hit.position = ray.origin + tBest * ray.direction;
    if (kind == PRIM_SPHERE) {
        Sphere s = BUF(spheres)[index];
        hit.normal = (hit.position - s.center) * (1.0f / s.radius);
        hit.material = s.material;
    } else if (kind == PRIM_PLANE) {
        hit.normal = BUF(planes)[index].normal;
        hit.material = BUF(planes)[index].material;
    } else if (kind == PRIM_QUAD) {
        hit.normal = unitVector(BUF(quads)[index].w);
        hit.material = BUF(quads)[index].material;
    } else {
        hit.normal = unitVector(cross(BUF(triangles)[index].edge1, BUF(triangles)[index].edge2));
        hit.material = BUF(triangles)[index].material;
    }
    return true;
}

// Whether anything lies on the segment from origin along direction within (0, tMax).
PH_FN bool traceOccluded(BUF_PARAM vec3 origin, vec3 direction, float tMax) {
    Ray ray = makeRay(origin, direction, tMax);
    for (uint i = 0u; i < BUF(params).scene.sphereCount; ++i) {
        if (intersectSphere(ray, BUF(spheres)[i].center, BUF(spheres)[i].radius, tMax) < tMax) {
            return true;
        }
    }
    for (uint i = 0u; i < BUF(params).scene.planeCount; ++i) {
        if (intersectPlane(ray, BUF(planes)[i].normal, BUF(planes)[i].offset, tMax) < tMax) {
            return true;
        }
    }
    for (uint i = 0u; i < BUF(params).scene.quadCount; ++i) {
        if (intersectQuad(ray, BUF(quads)[i], tMax) < tMax) {
            return true;
        }
    }
    for (uint i = 0u; i < BUF(params).scene.triangleCount; ++i) {
        if (intersectTriangle(ray, BUF(triangles)[i], tMax) < tMax) {
            return true;
        }
    }
    return false;
}

PH_NAMESPACE_END

#endif
