// The denoise stage: an edge-avoiding à-trous wavelet filter (Dammertz, Sewtz, Hanika & Lensch,
// HPG 2010) guided by each pixel's variance, as in spatiotemporal variance-guided filtering
// (Schied et al., HPG 2017, SVGF), over the accumulated image. Its passes, one dispatch each:
//   prepare  the radiance, less the pixel's background (aov.h: emitters and sky, added back as
//            they are), divided by the albedo (demodulation: the filter sees illumination, so
//            textures are not blurred), its variance (from the frames' luminance moments, or over
//            the 7 × 7 neighbours while a pixel has few frames) and the guides: unit normal, depth
//            and its slope |∇z|;
//   level i  a 3 × 3 binomial kernel (1 2 1)/4 with holes 2^i, each tap weighted by how alike
//            the two pixels' normals, depths, albedos and luminances are, the luminance relative
//            to the standard deviation. The last level multiplies the albedo back.
// The levels read 32 bytes a tap: the neighbour's radiance and variance, and its guides packed
// into 16 (DenoiseGuide), each from a plane of its own (constants.h), so that a warp's reads use
// every byte of the sectors they fetch.
// Three departures from SVGF, each measured against converged references (docs/denoising.md):
// - A 3 × 3 kernel, not SVGF's 5 × 5 B3 spline: over the same five levels it reaches 31 pixels,
//   not 62, with 9 taps, not 25, and on all five measured scenes it was as good or better (the
//   glass bunny 6.38% → 6.08% away from its caustic's focus, the sky 7.42% → 6.57%): a photon
//   map's blotches are a few pixels wide, and the wider reach smeared light across edges.
// - The variance is not filtered from level to level. SVGF divides it by the taps' weights as if
//   neighbours' noise were independent; a photon map's is not (neighbours share photons: its
//   noise is blotches, not grain), so the coarse levels would see too little variance to remove
//   the blotches. Every level uses the prepared variance.
// - The variance leaves the caustic map out (aov.h), so that a focus, whose frames vary by more
//   than its contrast, keeps its edges: its surroundings' variance is the global map's. (Left
//   out of the filter instead, the caustic map's speckle over the floor and walls stays.)
#ifndef PHOTON_SHARED_DENOISE_H
#define PHOTON_SHARED_DENOISE_H

#include "aov.h"

PH_NAMESPACE_BEGIN

// The binomial kernel's weights at offsets -1, 0 and 1 (1/4, 1/2, 1/4).
PH_FN float kernelWeight(int offset) { return offset == 0 ? 0.5f : 0.25f; }

PH_FN bool aovSurface(PH_IN(PixelAov) a) { return dot(a.normal, a.normal) > 1.0e-6f; }

// What the levels compare between two pixels.
struct DenoiseGuide {
    vec3 normal;  // as decoded, of length 1/√3 to 1 (normalWeight divides it out); 0: no surface
    vec3 albedo;  // to 10 bits a channel over [0, DENOISE_ALBEDO_RANGE]
    float depth;
    float slope;  // |∇z|, depth per pixel
};

PH_CONST uint DENOISE_SURFACE_BIT = 0x40000000u;

PH_FN uint quantizeAlbedo(float a) {
    return uint(floor(clamp(a, 0.0f, DENOISE_ALBEDO_RANGE) * (1023.0f / DENOISE_ALBEDO_RANGE) + 0.5f));
}

// 16 bytes: the normal in octahedral 2 × 16 bits (math.h), the albedo's three 10-bit channels and
// whether there is a surface, the depth and the slope as they are.
PH_FN uvec4 packDenoiseGuide(PH_IN(DenoiseGuide) g) {
    bool surface = dot(g.normal, g.normal) > 0.0f;
    uint albedo = quantizeAlbedo(g.albedo.x) | (quantizeAlbedo(g.albedo.y) << 10u) | (quantizeAlbedo(g.albedo.z) << 20u);
    return uvec4(surface ? octEncode(g.normal) : 0u, albedo | (surface ? DENOISE_SURFACE_BIT : 0u),
                 floatBitsToUint(g.depth), floatBitsToUint(g.slope));
}

PH_FN DenoiseGuide unpackDenoiseGuide(uvec4 bits) {
    DenoiseGuide g;
    g.normal = (bits.y & DENOISE_SURFACE_BIT) != 0u ? octDecodeUnnormalized(bits.x) : vec3(0.0f);
    g.albedo = vec3(float(bits.y & 1023u), float((bits.y >> 10u) & 1023u), float((bits.y >> 20u) & 1023u)) *
               (DENOISE_ALBEDO_RANGE / 1023.0f);
    g.depth = uintBitsToFloat(bits.z);
    g.slope = uintBitsToFloat(bits.w);
    return g;
}

// Where plane `plane` of `pixel` lies in the denoisePlanes buffer.
PH_FN uint denoiseSlot(BUF_PARAM uint plane, uint pixel) { return plane * BUF(params).width * BUF(params).height + pixel; }

PH_FN vec4 denoiseRadiance(BUF_PARAM uint plane, uint pixel) {
    return uintBitsToFloat(PH_LOAD_UVEC4(BUF(denoisePlanes)[denoiseSlot(BUF_ARG plane, pixel)]));
}

PH_FN DenoiseGuide denoiseGuide(BUF_PARAM uint pixel) {
    return unpackDenoiseGuide(PH_LOAD_UVEC4(BUF(denoisePlanes)[denoiseSlot(BUF_ARG DENOISE_PLANE_GUIDE, pixel)]));
}

// The smaller of the depth differences to the two neighbours along one axis (the side across a
// depth edge is not the surface's slope); -1 where neither neighbour has a depth.
PH_FN float depthStep(BUF_PARAM uint x, uint y, int dx, int dy, float z) {
    uint width = BUF(params).width;
    uint height = BUF(params).height;
    float best = -1.0f;
    for (int side = -1; side <= 1; side += 2) {
        int qx = int(x) + side * dx;
        int qy = int(y) + side * dy;
        if (qx < 0 || qy < 0 || qx >= int(width) || qy >= int(height)) {
            continue;
        }
        PixelAov q = BUF(aovs)[uint(qy) * width + uint(qx)];
        if (q.coverage > 0.0f) {
            float d = abs(q.depth - z);
            best = best < 0.0f ? d : min(best, d);
        }
    }
    return best;
}

// Pass prepare of one pixel.
PH_FN void denoisePrepare(BUF_PARAM uint pixel) {
    uint width = BUF(params).width;
    uint height = BUF(params).height;
    uint x = pixel % width;
    uint y = pixel / width;
    PixelAov a = BUF(aovs)[pixel];
    bool surface = aovSurface(a);
    vec3 illumination = (vec3(BUF(accumulation)[pixel]) - a.background) / demodulation(a.albedo, surface);
    uint frames = max(uint(a.frames), 1u);  // this frame's included (history.h)

    // The variance of the mean of `frames` frames: the pixel's own moments, or while they are
    // few its neighbours' on the same surface.
    float mean = a.luminance;
    float mean2 = a.luminance2;
    vec3 normal = surface ? unitVector(a.normal) : vec3(0.0f);
    if (frames < DENOISE_TEMPORAL_FRAMES && surface) {
        float sum = 0.0f;
        float sum2 = 0.0f;
        float weights = 0.0f;
        for (int dy = -3; dy <= 3; ++dy) {
            for (int dx = -3; dx <= 3; ++dx) {
                int qx = int(x) + dx;
                int qy = int(y) + dy;
                if (qx < 0 || qy < 0 || qx >= int(width) || qy >= int(height)) {
                    continue;
                }
                PixelAov q = BUF(aovs)[uint(qy) * width + uint(qx)];
                if (!aovSurface(q)) {
                    continue;
                }
                float w = max(dot(normal, unitVector(q.normal)), 0.0f);
                sum += w * q.luminance;
                sum2 += w * q.luminance2;
                weights += w;
            }
        }
        mean = sum / weights;
        mean2 = sum2 / weights;
    }
    // The moments are of the radiance: its variance divided by the albedo's luminance squared is
    // that of the illumination the levels filter.
    float scale = luminanceOf(demodulation(a.albedo, surface));
    float variance = max(mean2 - mean * mean, 0.0f) / (float(frames) * scale * scale);
    if (!(variance <= FLOAT_MAX)) {
        variance = FLOAT_MAX;  // moments that overflowed (an absurd radius): no luminance weight
    }

    float slopeX = depthStep(BUF_ARG x, y, 1, 0, a.depth);
    float slopeY = depthStep(BUF_ARG x, y, 0, 1, a.depth);
    DenoiseGuide guide;
    guide.normal = normal;
    guide.albedo = a.albedo;
    guide.depth = a.coverage > 0.0f ? a.depth : 0.0f;
    guide.slope = length(vec2(max(slopeX, 0.0f), max(slopeY, 0.0f)));
    PH_STORE_UVEC4(BUF(denoisePlanes)[denoiseSlot(BUF_ARG DENOISE_PLANE_RADIANCE, pixel)],
                   floatBitsToUint(vec4(illumination, variance)));
    PH_STORE_UVEC4(BUF(denoisePlanes)[denoiseSlot(BUF_ARG DENOISE_PLANE_GUIDE, pixel)], packDenoiseGuide(guide));
}

// The normal weight cos^(2^DENOISE_NORMAL_SQUARINGS) of the angle between the unit normal n and
// m, of any length (a decoded guide's): (n·m)² / |m|² is cos², squared on; no square root.
PH_FN float normalWeight(vec3 n, vec3 m) {
    float d = dot(n, m);
    if (d <= 0.0f) {
        return 0.0f;
    }
    float y = PH_WEIGHT_DIVIDE(d * d, dot(m, m));
    for (uint i = 1u; i < DENOISE_NORMAL_SQUARINGS; ++i) {
        y *= y;
    }
    return y;
}

// The variance about a pixel, 3 × 3 Gaussian-weighted: one pixel's own estimate is too noisy to
// scale the luminance weight with (SVGF).
PH_FN float blurredVariance(BUF_PARAM uint x, uint y, uint plane) {
    uint width = BUF(params).width;
    uint height = BUF(params).height;
    float sum = 0.0f;
    float weights = 0.0f;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            int qx = int(x) + dx;
            int qy = int(y) + dy;
            if (qx < 0 || qy < 0 || qx >= int(width) || qy >= int(height)) {
                continue;
            }
            float w = (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
            sum += w * uintBitsToFloat(BUF(denoisePlanes)[denoiseSlot(BUF_ARG plane, uint(qy) * width + uint(qx))].w);
            weights += w;
        }
    }
    return sum / weights;
}

// Pass `level` (0 .. DENOISE_LEVELS - 1) of one pixel: reads plane level % 2, writes the other;
// the last level writes the image into `denoised`.
PH_FN void denoiseLevel(BUF_PARAM uint pixel, uint level) {
    uint width = BUF(params).width;
    uint height = BUF(params).height;
    uint x = pixel % width;
    uint y = pixel / width;
    uint source = DENOISE_PLANE_RADIANCE + (level & 1u);
    vec4 centre = denoiseRadiance(BUF_ARG source, pixel);
    DenoiseGuide guide = denoiseGuide(BUF_ARG pixel);
    vec4 filtered = centre;
    if (dot(guide.normal, guide.normal) > 0.0f) {
        vec3 normal = unitVector(guide.normal);
        float luminance = luminanceOf(vec3(centre));
        // Level 0 blurs the variance and passes it on: the levels all use the same.
        float variance = level == 0u ? blurredVariance(BUF_ARG x, y, source) : centre.w;
        float toSigmasL = 1.0f / (DENOISE_SIGMA_LUMINANCE * sqrt(variance) + 1.0e-6f);
        float reach = DENOISE_SIGMA_DEPTH * guide.slope;
        float depthFloor = 1.0e-3f * guide.depth + 1.0e-6f;
        int hole = 1 << int(level);
        vec3 sum = vec3(0.0f);
        float weights = 0.0f;
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                int qx = int(x) + dx * hole;
                int qy = int(y) + dy * hole;
                if (qx < 0 || qy < 0 || qx >= int(width) || qy >= int(height)) {
                    continue;
                }
                float h = kernelWeight(dx) * kernelWeight(dy);
                vec4 c = centre;
                float w = 1.0f;
                if (dx != 0 || dy != 0) {
                    uint q = uint(qy) * width + uint(qx);
                    c = denoiseRadiance(BUF_ARG source, q);
                    if (!isFinite(vec3(c))) {
                        continue;  // no neighbour's overflow reaches this pixel
                    }
                    DenoiseGuide g = denoiseGuide(BUF_ARG q);
                    float wn = normalWeight(normal, g.normal);
                    float distance = float(hole) * length(vec2(float(dx), float(dy)));
                    float wz = PH_WEIGHT_DIVIDE(abs(guide.depth - g.depth), reach * distance + depthFloor);
                    float wl = abs(luminance - luminanceOf(vec3(c))) * toSigmasL;
                    vec3 da = abs(guide.albedo - g.albedo);
                    float wa = (da.x + da.y + da.z) * (1.0f / DENOISE_SIGMA_ALBEDO);
                    w = wn * PH_WEIGHT_EXP(-wz - wl - wa);
                }
                sum += (h * w) * vec3(c);
                weights += h * w;
            }
        }
        filtered = vec4(sum / weights, variance);
        if (!isFinite(vec3(filtered))) {
            filtered = centre;  // the sums overflowed
        }
    }
    if (level + 1u < DENOISE_LEVELS) {
        PH_STORE_UVEC4(BUF(denoisePlanes)[denoiseSlot(BUF_ARG DENOISE_PLANE_RADIANCE + ((level + 1u) & 1u), pixel)], floatBitsToUint(filtered));
        return;
    }
    PixelAov a = BUF(aovs)[pixel];
    vec3 image = vec3(filtered) * demodulation(a.albedo, aovSurface(a)) + a.background;
    if (!isFinite(image)) {
        image = vec3(BUF(accumulation)[pixel]);  // a finite image stays finite
    }
    BUF(denoised)[pixel] = vec4(image, 1.0f);
}

// One pass of STAGE_DENOISE (DENOISE_PASS_*) at one pixel.
PH_FN void denoisePass(BUF_PARAM uint pixel, uint pass) {
    if (pass == DENOISE_PASS_PREPARE) {
        denoisePrepare(BUF_ARG pixel);
    } else {
        denoiseLevel(BUF_ARG pixel, pass - DENOISE_PASS_LEVEL);
    }
}

PH_NAMESPACE_END

#endif
