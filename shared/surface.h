// What the light transport sees of a surface where a ray met it: the point, its geometric normal
// (for ray offsets and for which side light comes from, so that nothing leaks through at
// silhouettes), its shading normal (interpolated vertex normals, for BSDFs and cosines), and its
// material with the albedo its texture gives there.
#ifndef PHOTON_SHARED_SURFACE_H
#define PHOTON_SHARED_SURFACE_H

#include "intersect.h"
#include "material.h"
#include "texture.h"

PH_NAMESPACE_BEGIN

struct SurfacePoint {
    vec3 position;
    vec3 geometricNormal;  // unit; the primitive's own side (outward for spheres)
    vec3 shadingNormal;    // unit; on the geometric normal's side
    Material material;     // albedo textured
};

PH_FN SurfacePoint surfaceAt(BUF_PARAM PH_IN(Hit) hit) {
    SurfacePoint sp;
    sp.position = hit.position;
    sp.geometricNormal = hit.normal;
    sp.shadingNormal = hit.normal;
    sp.material = BUF(materials)[hit.material];
    if (hit.kind != PRIM_TRIANGLE) {
        return sp;
    }
    uint a = BUF(triangles)[hit.index].attributes;
    if (a == NONE) {
        return sp;
    }
    TriangleAttributes attributes = BUF(triangleAttributes)[a];
    float b0 = 1.0f - hit.b1 - hit.b2;
    if ((attributes.flags & ATTRIBUTE_NORMALS) != 0u) {
        vec3 n = octDecode(attributes.normal0) * b0 + octDecode(attributes.normal1) * hit.b1 +
                 octDecode(attributes.normal2) * hit.b2;
        float length2 = dot(n, n);
        if (length2 > 1.0e-12f) {
            n = n * (1.0f / sqrt(length2));
            sp.shadingNormal = dot(n, hit.normal) < 0.0f ? -n : n;
        }
    }
    if ((attributes.flags & ATTRIBUTE_TEXCOORDS) != 0u && sp.material.albedoTexture != NONE) {
        float s = attributes.s0 * b0 + attributes.s1 * hit.b1 + attributes.s2 * hit.b2;
        float t = attributes.t0 * b0 + attributes.t1 * hit.b1 + attributes.t2 * hit.b2;
        sp.material.albedo = sp.material.albedo * sampleTexture(BUF_ARG sp.material.albedoTexture, s, t);
    }
    return sp;
}

PH_NAMESPACE_END

#endif
