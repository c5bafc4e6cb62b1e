// What the light transport sees of a surface where a ray met it: the point, its geometric normal
// (for ray offsets and for which side light comes from, so that nothing leaks through at
// silhouettes), its shading normal (interpolated vertex normals and the normal texture, for BSDFs
// and cosines), and its material as its textures make it there (albedo, metallic, roughness,
// emission), at the frame's wavelengths under spectral rendering.
#ifndef PHOTON_SHARED_SURFACE_H
#define PHOTON_SHARED_SURFACE_H

#include "intersect.h"
#include "material.h"
#include "spectral.h"
#include "texture.h"

PH_NAMESPACE_BEGIN

struct SurfacePoint {
    vec3 position;
    vec3 geometricNormal;  // unit; the primitive's own side (outward for spheres)
    vec3 shadingNormal;    // unit; on the geometric normal's side
    Material material;     // textured
};

// A tangent-space normal texture (glTF's: x along the tangent, y along the bitangent n × t, both
// scaled by normalScale) applied to the shading normal ns. A result on the wrong side of the
// geometric surface keeps ns.
PH_FN vec3 normalMapped(BUF_PARAM PH_IN(Material) m, PH_IN(TriangleAttributes) attributes, vec2 st, vec3 ns, vec3 ng) {
    vec3 texel = vec3(sampleTexture(BUF_ARG m.normalTexture, st.x, st.y)) * 2.0f - vec3(1.0f);
    vec3 t = octDecode(attributes.tangent);
    t = t - ns * dot(ns, t);
    float length2 = dot(t, t);
    if (!(length2 > 1.0e-12f)) {
        return ns;
    }
    t = t * (1.0f / sqrt(length2));
    vec3 b = cross(ns, t);
    if ((attributes.flags & ATTRIBUTE_FLIPPED_BITANGENT) != 0u) {
        b = -b;
    }
    vec3 n = t * (texel.x * m.normalScale) + b * (texel.y * m.normalScale) + ns * texel.z;
    float n2 = dot(n, n);
    if (!(n2 > 1.0e-12f)) {
        return ns;
    }
    n = n * (1.0f / sqrt(n2));
    return dot(n, ng) > 0.0f ? n : ns;
}

PH_FN SurfacePoint texturedSurfaceAt(BUF_PARAM PH_IN(Hit) hit) {
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
    if ((attributes.flags & ATTRIBUTE_TEXCOORDS) == 0u) {
        return sp;
    }
    vec2 st = texcoordsAt(attributes, hit.b1, hit.b2);
    if (sp.material.albedoTexture != NONE) {
        sp.material.albedo = sp.material.albedo * vec3(sampleTexture(BUF_ARG sp.material.albedoTexture, st.x, st.y));
    }
    if (sp.material.metallicRoughnessTexture != NONE) {
        vec4 mr = sampleTexture(BUF_ARG sp.material.metallicRoughnessTexture, st.x, st.y);
        sp.material.metallic = sp.material.metallic * mr.z;
        sp.material.roughness = sp.material.roughness * (mr.y * mr.y);  // α = (factor · texel)²
    }
    if (sp.material.emissionTexture != NONE) {
        sp.material.emission = sp.material.emission * vec3(sampleTexture(BUF_ARG sp.material.emissionTexture, st.x, st.y));
    }
    if (sp.material.normalTexture != NONE && (attributes.flags & ATTRIBUTE_TANGENT) != 0u) {
        sp.shadingNormal = normalMapped(BUF_ARG sp.material, attributes, st, sp.shadingNormal, sp.geometricNormal);
    }
    return sp;
}

// The surface as light transport sees it: textured, its colours at the frame's wavelengths.
PH_FN SurfacePoint surfaceAt(BUF_PARAM PH_IN(Hit) hit) {
    SurfacePoint sp = texturedSurfaceAt(BUF_ARG hit);
    sp.material = spectralMaterial(BUF_ARG sp.material);
    return sp;
}

PH_NAMESPACE_END

#endif
