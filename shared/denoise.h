// The denoise stage: an edge-avoiding à-trous wavelet filter (Dammertz, Sewtz, Hanika & Lensch,
// HPG 2010) guided by each pixel's variance, as in spatiotemporal variance-guided filtering
// (Schied et al., HPG 2017, SVGF), over the accumulated image. Its passes, one dispatch each:
//   prepare  the radiance, less the pixel's background (aov.h: emitters and sky, added back as
//            they are), divided by the albedo (demodulation: the filter sees illumination, so
//            textures are not blurred), its variance (from the frames' luminance moments, or over
//            the 7 × 7 neighbours while a pixel has few frames) and the guides: unit normal, depth
//            and its slope |∇z|;
//   variance the variance blurred 3 × 3 (SVGF), once for all levels;
//   level i  a 3 × 3 binomial kernel (1 2 1)/4 with holes 2^i, each tap weighted by how alike
//            the two pixels' normals, depths, albedos and luminances are, the luminance relative
//            to the larger standard deviation of the two; a first pass sums each pixel's weights,
//            the second moves light between pixels by them so that none is made or lost (a
//            doubly stochastic filter: denoiseLevel). The last level multiplies the albedo back.
// A level's weights pass reads 32 bytes a tap, the neighbour's radiance and standard deviation and
// its guides packed into 16 (DenoiseGuide), and writes the pixel's eight tap weights and their
// sum; the level reads them and 20 bytes a tap (radiance, the neighbour's sum). Each is a plane of
// its own (constants.h), so that a warp's reads use every byte of the sectors they fetch.
// Four departures from SVGF, each measured against converged references (docs/denoising.md):
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
// - Doubly stochastic levels (above), where SVGF's normalize each pixel's weights and so move
//   light toward pixels with few similar neighbours: the image's mean within 1% of the raw
//   one's at every size (1 × N included) and in every view.
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

// Pass variance of one pixel: the prepared plane into the other, its variance blurred and as a
// standard deviation (the levels all use the same, their own and each neighbour's).
PH_FN void denoiseVariance(BUF_PARAM uint pixel) {
    uint width = BUF(params).width;
    vec4 own = denoiseRadiance(BUF_ARG DENOISE_PLANE_RADIANCE, pixel);
    own.w = sqrt(blurredVariance(BUF_ARG pixel % width, pixel / width, DENOISE_PLANE_RADIANCE));
    PH_STORE_UVEC4(BUF(denoisePlanes)[denoiseSlot(BUF_ARG DENOISE_PLANE_RADIANCE + 1u, pixel)], floatBitsToUint(own));
}

// The weight of the tap from pixel p to its neighbour q of a level (kernel times edge-stopping),
// the same seen from either pixel: each term takes the larger of the two pixels' variance, slope
// and depth, and the normal weight is the squared cosine of both.
PH_FN float denoiseTapWeight(PH_IN(DenoiseGuide) guide, vec3 normal, vec4 centre, PH_IN(DenoiseGuide) g, vec4 c, int dx,
                             int dy, int hole) {
    float wn = normalWeight(normal, g.normal);
    if (wn == 0.0f) {
        return 0.0f;
    }
    float distance = float(hole) * length(vec2(float(dx), float(dy)));
    float reach = DENOISE_SIGMA_DEPTH * max(guide.slope, g.slope);
    float depthFloor = 1.0e-3f * max(guide.depth, g.depth) + 1.0e-6f;
    float wz = PH_WEIGHT_DIVIDE(abs(guide.depth - g.depth), reach * distance + depthFloor);
    float sigmaL = DENOISE_SIGMA_LUMINANCE * max(centre.w, c.w) + 1.0e-6f;
    float wl = PH_WEIGHT_DIVIDE(abs(luminanceOf(vec3(centre)) - luminanceOf(vec3(c))), sigmaL);
    vec3 da = abs(guide.albedo - g.albedo);
    float wa = (da.x + da.y + da.z) * (1.0f / DENOISE_SIGMA_ALBEDO);
    return kernelWeight(dx) * kernelWeight(dy) * wn * PH_WEIGHT_EXP(-wz - wl - wa);
}

PH_FN float denoiseWeightSum(BUF_PARAM uint pixel) {
    return uintBitsToFloat(BUF(denoisePlanes)[denoiseSlot(BUF_ARG DENOISE_PLANE_WEIGHTS, pixel)].x);
}

// The source plane of level `level` (the variance pass writes plane 1, then the levels alternate).
PH_FN uint denoiseSource(uint level) { return DENOISE_PLANE_RADIANCE + ((level + 1u) & 1u); }

// Tap k (0 … 7) of the 3 × 3 kernel without its centre, row by row.
PH_FN ivec2 denoiseTap(uint k) {
    uint i = k < 4u ? k : k + 1u;
    return ivec2(int(i % 3u) - 1, int(i / 3u) - 1);
}

// A level's first pass at one pixel: the weight of each tap (0 where the neighbour lies outside
// the image or holds no finite radiance) into the two tap planes, and their sum with the kernel's
// centre (1/4) into the weights plane. A pixel without a surface has its own tap alone.
PH_FN void denoiseWeights(BUF_PARAM uint pixel, uint level) {
    uint width = BUF(params).width;
    uint height = BUF(params).height;
    uint x = pixel % width;
    uint y = pixel / width;
    uint source = denoiseSource(level);
    vec4 centre = denoiseRadiance(BUF_ARG source, pixel);
    DenoiseGuide guide = denoiseGuide(BUF_ARG pixel);
    float taps[8];
    float weights = kernelWeight(0) * kernelWeight(0);
    bool filters = dot(guide.normal, guide.normal) > 0.0f && isFinite(vec3(centre));
    vec3 normal = filters ? unitVector(guide.normal) : vec3(0.0f);
    int hole = 1 << int(level);
    for (uint k = 0u; k < 8u; ++k) {
        ivec2 d = denoiseTap(k);
        int qx = int(x) + d.x * hole;
        int qy = int(y) + d.y * hole;
        taps[k] = 0.0f;
        if (!filters || qx < 0 || qy < 0 || qx >= int(width) || qy >= int(height)) {
            continue;
        }
        uint q = uint(qy) * width + uint(qx);
        vec4 c = denoiseRadiance(BUF_ARG source, q);
        if (isFinite(vec3(c))) {
            taps[k] = denoiseTapWeight(guide, normal, centre, denoiseGuide(BUF_ARG q), c, d.x, d.y, hole);
            weights += taps[k];
        }
    }
    BUF(denoisePlanes)[denoiseSlot(BUF_ARG DENOISE_PLANE_WEIGHTS, pixel)] = uvec4(floatBitsToUint(weights), 0u, 0u, 0u);
    PH_STORE_UVEC4(BUF(denoisePlanes)[denoiseSlot(BUF_ARG DENOISE_PLANE_TAPS, pixel)],
                   floatBitsToUint(vec4(taps[0], taps[1], taps[2], taps[3])));
    PH_STORE_UVEC4(BUF(denoisePlanes)[denoiseSlot(BUF_ARG DENOISE_PLANE_TAPS + 1u, pixel)],
                   floatBitsToUint(vec4(taps[4], taps[5], taps[6], taps[7])));
}

// Pass `level` (0 .. DENOISE_LEVELS - 1) of one pixel: reads plane denoiseSource(level), writes
// the other; the last level writes the image into `denoised`. A doubly stochastic filter:
//   x'_p = x_p + Σ_q w_pq (x_q − x_p) / max(W_p, W_q),   W_p = Σ_q w_pq (the weights pass),
// with w_pq = w_qp. Its rows sum to 1, so a constant stays constant, and as w_pq / max(W_p, W_q) is
// symmetric its columns do too, so the light a pixel gives is the light its neighbours take: the
// image keeps its energy at every size and in every view. (A gather x_p = Σ w_pq x_q / W_p keeps
// constants but not energy: a noisy bright pixel gave its light to quiet dark neighbours, whose
// few similar neighbours made their W small; 22% of a 1 × 2000 image was lost, issue 57.) Each
// tap's share is at most its gather weight, the rest staying with the pixel.
PH_FN void denoiseLevel(BUF_PARAM uint pixel, uint level) {
    uint width = BUF(params).width;
    uint x = pixel % width;
    uint y = pixel / width;
    uint source = denoiseSource(level);
    vec4 centre = denoiseRadiance(BUF_ARG source, pixel);
    vec4 filtered = centre;
    float own = denoiseWeightSum(BUF_ARG pixel);
    if (own > kernelWeight(0) * kernelWeight(0)) {  // a neighbour takes part
        vec4 near = uintBitsToFloat(PH_LOAD_UVEC4(BUF(denoisePlanes)[denoiseSlot(BUF_ARG DENOISE_PLANE_TAPS, pixel)]));
        vec4 far = uintBitsToFloat(PH_LOAD_UVEC4(BUF(denoisePlanes)[denoiseSlot(BUF_ARG DENOISE_PLANE_TAPS + 1u, pixel)]));
        float taps[8] = {near.x, near.y, near.z, near.w, far.x, far.y, far.z, far.w};
        int hole = 1 << int(level);
        vec3 change = vec3(0.0f);
        for (uint k = 0u; k < 8u; ++k) {
            if (taps[k] > 0.0f) {
                ivec2 d = denoiseTap(k);
                uint q = uint(int(y) + d.y * hole) * width + uint(int(x) + d.x * hole);
                vec3 c = vec3(denoiseRadiance(BUF_ARG source, q));
                change += PH_WEIGHT_DIVIDE(taps[k], max(own, denoiseWeightSum(BUF_ARG q))) * (c - vec3(centre));
            }
        }
        filtered = vec4(vec3(centre) + change, centre.w);
        if (!isFinite(vec3(filtered))) {
            filtered = centre;  // the sums overflowed
        }
    }
    if (level + 1u < DENOISE_LEVELS) {
        PH_STORE_UVEC4(BUF(denoisePlanes)[denoiseSlot(BUF_ARG DENOISE_PLANE_RADIANCE + (level & 1u), pixel)], floatBitsToUint(filtered));
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
    } else if (pass == DENOISE_PASS_VARIANCE) {
        denoiseVariance(BUF_ARG pixel);
    } else if (((pass - DENOISE_PASS_LEVEL) & 1u) == 0u) {
        denoiseWeights(BUF_ARG pixel, (pass - DENOISE_PASS_LEVEL) / 2u);
    } else {
        denoiseLevel(BUF_ARG pixel, (pass - DENOISE_PASS_LEVEL) / 2u);
    }
}

PH_NAMESPACE_END

#endif
