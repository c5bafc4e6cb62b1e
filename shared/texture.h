// Base-colour textures: texels in linear RGBA with 16 bits a channel (the host decodes sRGB, so that
// no transcendental function runs here), filtered bilinearly with the glTF sampler's wrap modes.
// Integer and + - * / arithmetic only: every backend samples the same value.
#ifndef PHOTON_SHARED_TEXTURE_H
#define PHOTON_SHARED_TEXTURE_H

#include "bindings.h"

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

PH_FN vec3 loadTexel(BUF_PARAM PH_IN(Texture) texture, int x, int y) {
    uvec2 packed = BUF(texels)[texture.offset + uint(y) * texture.width + uint(x)];
    return vec3(float(packed.x & 0xffffu), float(packed.x >> 16u), float(packed.y & 0xffffu)) * (1.0f / 65535.0f);
}

// The texture's colour at (s, t): s runs left to right, t top to bottom (glTF's convention; the
// OBJ loader flips its t).
PH_FN vec3 sampleTexture(BUF_PARAM uint index, float s, float t) {
    Texture texture = BUF(textures)[index];
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
    vec3 top = loadTexel(BUF_ARG texture, ix0, iy0) * (1.0f - fx) + loadTexel(BUF_ARG texture, ix1, iy0) * fx;
    vec3 bottom = loadTexel(BUF_ARG texture, ix0, iy1) * (1.0f - fx) + loadTexel(BUF_ARG texture, ix1, iy1) * fx;
    return top * (1.0f - fy) + bottom * fy;
}

PH_NAMESPACE_END

#endif
