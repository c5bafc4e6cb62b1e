// Textures: texels in linear RGBA with 16 bits a channel (the host decodes sRGB colour, so that no
// transcendental function runs here), filtered bilinearly with the glTF sampler's wrap modes, and
// the coverage (alpha) test of cut-out and blended surfaces. Integer and + - * / arithmetic only:
// every backend samples the same value.
#ifndef PHOTON_SHARED_TEXTURE_H
#define PHOTON_SHARED_TEXTURE_H

#include "bindings.h"
#include "rng.h"

PH_NAMESPACE_BEGIN

PH_CONST uint TEXTURE_SIZE_MAX = 8192u;  // texels along an edge (the host refuses larger images)

// Texel column or row i of an image n wide under a wrap mode. (GLSL leaves % of negative numbers
// undefined: i is moved up by a multiple of the period first, which sampleTexture's clamp of its
// coordinates and TEXTURE_SIZE_MAX keep within 32 bits.)
PH_FN int wrapTexel(int i, int n, uint mode) {
    if (mode == WRAP_CLAMP) {
        return clamp(i, 0, n - 1);
    }
    uint period = 2u * uint(n);
    uint u = uint(i + int(period) * 65537);
    if (mode == WRAP_MIRRORED_REPEAT) {
        uint m = u % period;
        return int(m < uint(n) ? m : period - 1u - m);
    }
    return int(u % uint(n));
}

PH_FN vec4 loadTexel(BUF_PARAM PH_IN(Texture) texture, int x, int y) {
    uvec2 packed = BUF(texels)[texture.offset + uint(y) * texture.width + uint(x)];
    return vec4(float(packed.x & 0xffffu), float(packed.x >> 16u), float(packed.y & 0xffffu), float(packed.y >> 16u)) *
           (1.0f / 65535.0f);
}

// The texture's colour and alpha at (s, t), after its transform: s runs left to right, t top to
// bottom (glTF's convention; the OBJ loader flips its t).
PH_FN vec4 sampleTexture(BUF_PARAM uint index, float s0, float t0) {
    Texture texture = BUF(textures)[index];
    float s = dot(texture.transformS, vec3(s0, t0, 1.0f));
    float t = dot(texture.transformT, vec3(s0, t0, 1.0f));
    int w = int(texture.width);
    int h = int(texture.height);
    // Coordinates far outside [0, 1] wrap the same; keeping them small keeps floor() exact.
    float x = clamp(s, -65536.0f, 65536.0f) * float(w) - 0.5f;
    float y = clamp(t, -65536.0f, 65536.0f) * float(h) - 0.5f;
    float x0 = floor(x);
    float y0 = floor(y);
    float fx = x - x0;
    float fy = y - y0;
    uint wrapS = texture.wrap & 15u;
    uint wrapT = texture.wrap >> 4u;
    int ix0 = wrapTexel(int(x0), w, wrapS);
    int ix1 = wrapTexel(int(x0) + 1, w, wrapS);
    int iy0 = wrapTexel(int(y0), h, wrapT);
    int iy1 = wrapTexel(int(y0) + 1, h, wrapT);
    vec4 top = loadTexel(BUF_ARG texture, ix0, iy0) * (1.0f - fx) + loadTexel(BUF_ARG texture, ix1, iy0) * fx;
    vec4 bottom = loadTexel(BUF_ARG texture, ix0, iy1) * (1.0f - fx) + loadTexel(BUF_ARG texture, ix1, iy1) * fx;
    return top * (1.0f - fy) + bottom * fy;
}

// The texture coordinates of a triangle's point of barycentric weights (b1, b2).
PH_FN vec2 texcoordsAt(PH_IN(TriangleAttributes) a, float b1, float b2) {
    float b0 = 1.0f - b1 - b2;
    return vec2(a.s0 * b0 + a.s1 * b1 + a.s2 * b2, a.t0 * b0 + a.t1 * b1 + a.t2 * b2);
}

// The radiance a triangle's material emits at its point (b1, b2): the emission factor times the
// emission texture.
PH_FN vec3 triangleEmission(BUF_PARAM PH_IN(Triangle) tri, float b1, float b2) {
    Material m = BUF(materials)[tri.material];
    if (m.emissionTexture == NONE || tri.attributes == NONE) {
        return m.emission;
    }
    TriangleAttributes a = BUF(triangleAttributes)[tri.attributes];
    if ((a.flags & ATTRIBUTE_TEXCOORDS) == 0u) {
        return m.emission;
    }
    vec2 st = texcoordsAt(a, b1, b2);
    return m.emission * vec3(sampleTexture(BUF_ARG m.emissionTexture, st.x, st.y));
}

// Whether a triangle's point (b1, b2) is there for rays: its material's coverage α (factor times
// the base-colour texture's alpha) against the cutoff (MASK), or against a hash of the point and
// the ray (BLEND: stochastic transparency, so that the surface is present with probability α).
PH_FN bool coverageHolds(BUF_PARAM PH_IN(Triangle) tri, float b1, float b2, vec3 direction) {
    Material m = BUF(materials)[tri.material];
    float alpha = m.alpha;
    if (m.albedoTexture != NONE && tri.attributes != NONE) {
        TriangleAttributes a = BUF(triangleAttributes)[tri.attributes];
        if ((a.flags & ATTRIBUTE_TEXCOORDS) != 0u) {
            vec2 st = texcoordsAt(a, b1, b2);
            alpha *= sampleTexture(BUF_ARG m.albedoTexture, st.x, st.y).w;
        }
    }
    if ((m.flags & MATERIAL_FLAG_ALPHA_MASK) != 0u) {
        return alpha >= m.alphaCutoff;
    }
    uvec4 h = pcg4d(uvec4(floatBitsToUint(b1), floatBitsToUint(b2), floatBitsToUint(direction.x) ^ floatBitsToUint(direction.z),
                          floatBitsToUint(direction.y)));
    return float(h.x >> 8u) * (1.0f / 16777216.0f) < alpha;
}

PH_NAMESPACE_END

#endif
