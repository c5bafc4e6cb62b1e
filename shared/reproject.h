// The reproject stage: temporal reprojection (as in SVGF, Schied et al., HPG 2017) of a photon
// mapper's per-pixel history. When the camera has moved since the frame before (FLAG_REPROJECT),
// each pixel takes over the means of the pixels that saw its surface then, instead of starting
// again. Its passes, one dispatch each:
//   save     every pixel's means (sppm's statistics, the running mean, the auxiliary images) set
//            aside into `history`, so that the next pass reads the frame before's whatever order
//            pixels run in;
//   restore  where the pixel's surface appears now ("motion from depth": its depth along the ray
//            through the pixel's centre) projected into the previous camera, and the histories of
//            the four pixels about that point that saw the same surface, bilinearly weighted:
//            each one's mean depth within REPROJECT_DEPTH_TOLERANCE of the point's distance from
//            the previous camera and its mean normal's direction within acos(REPROJECT_NORMAL_COS)
//            of the point's. Where none did (the surface came into view, or another surface was
//            there) the pixel starts again (history.h: zero frames).
// The depth is the path's length through mirrors and glass (aov.h), so what a mirror shows moves
// as its virtual image does. Each carried history counts at most REPROJECT_MAX_FRAMES frames, so
// that the blur each move's interpolation adds gives way to new frames.
#ifndef PHOTON_SHARED_REPROJECT_H
#define PHOTON_SHARED_REPROJECT_H

#include "aov.h"
#include "eye_trace.h"

PH_NAMESPACE_BEGIN

// Pass save of one pixel. Member by member: glslang stores a whole struct with an array member
// into a buffer with invalid SPIR-V.
PH_FN void reprojectSave(BUF_PARAM uint pixel) {
    if (BUF(params).estimator == ESTIMATOR_SPPM) {
        BUF(history)[pixel].sppm.direct = BUF(sppmPixels)[pixel].direct;
        for (uint m = 0u; m < MAP_COUNT; ++m) {
            BUF(history)[pixel].sppm.maps[m].flux = BUF(sppmPixels)[pixel].maps[m].flux;
            BUF(history)[pixel].sppm.maps[m].radius = BUF(sppmPixels)[pixel].maps[m].radius;
            BUF(history)[pixel].sppm.count[m] = BUF(sppmPixels)[pixel].count[m];
        }
    }
    BUF(history)[pixel].accumulation = BUF(accumulation)[pixel];
    BUF(history)[pixel].aov = BUF(aovs)[pixel];
}

// Where the pixel's surface appears: along the ray through the pixel's centre at the path's
// length to the surface of the auxiliary images. Seen directly that is the surface itself; in a
// mirror or through glass, its image (exact for a flat mirror, whose virtual image lies behind
// it; for curved glass as far as the image holds still). Where the path met no such surface (the
// sky, an emitter) w is 0 and xyz the ray's direction. The centre, not this frame's jittered ray:
// a still camera must find each pixel's own history, and a moving one neighbouring pixels'
// distinct histories. (A jittered ray would pick a random neighbour's each frame, and histories
// would be copied twice or lost at random until the image was blotches of a few ancestors.)
PH_FN vec4 apparentPoint(BUF_PARAM uint pixel, PH_IN(HitPoint) hp) {
    uint width = BUF(params).width;
    Rng unused = rngCreate(pixel, 0u, 0u, STREAM_CAMERA);
    Ray ray = cameraRay(BUF(params).camera, pixel % width, pixel / width, width, BUF(params).height,
                        FLAG_PIXEL_CENTER, unused);
    if (!(hp.pathLength > 0.0f)) {
        return vec4(ray.direction, 0.0f);
    }
    return vec4(ray.origin + ray.direction * hp.pathLength, 1.0f);
}

// Whether a pixel of the frame before, with these auxiliary images, saw the surface that now
// appears at `point` (apparentPoint), `expected` from the previous camera, with normal n. A frame
// whose path met no surface (w 0) takes only a history that never met one either: the sky's.
PH_FN bool sawSameSurface(PH_IN(PixelAov) before, vec4 point, float expected, vec3 n, bool specular) {
    if (!(before.frames > 0.0f)) {
        return false;
    }
    if (point.w == 0.0f) {
        return before.coverage == 0.0f;
    }
    if (!(before.coverage > 0.0f)) {
        return false;
    }
    float tolerance = specular ? REPROJECT_SPECULAR_DEPTH_TOLERANCE : REPROJECT_DEPTH_TOLERANCE;
    bool sameDepth = abs(before.depth - expected) <= tolerance * expected;
    bool sameNormal = specular || dot(before.normal, n) >= REPROJECT_NORMAL_COS * length(before.normal);
    return sameDepth && sameNormal;
}

// Pass restore of one pixel: the histories of the four pixels of the frame before whose centres
// surround where its surface appeared then, each that saw the same surface weighted bilinearly
// (SVGF's rule). Means are interpolated as they are; sppm's statistics as the radiance they give,
// τ / (k π R²), with R and N, from which τ is made again for the carried frame count k: a photon
// mapper's radius, count and flux do not interpolate, but the estimate they hold does. (The
// nearest pixel alone would copy some histories twice and lose others wherever the image
// stretches, and after a few moves the image would be blotches of a few ancestors.)
PH_FN void reprojectRestore(BUF_PARAM uint pixel) {
    HitPoint hp = BUF(hitPoints)[pixel];
    vec4 point = apparentPoint(BUF_ARG pixel, hp);
    uint width = BUF(params).width;
    uint height = BUF(params).height;
    Camera previous = BUF(params).previousCamera;
    vec3 p = point.w == 0.0f ? previous.position + vec3(point) : vec3(point);
    vec3 q = projectToPixel(previous, p, width, height);
    float expected = length(p - previous.position);
    // A path through mirrors or glass is longer than the way to where it ended. Through a curved
    // surface its length and the surface it meets change from frame to frame with where in the
    // pixel the ray went: its depth is held to a looser tolerance, and its normal not at all.
    bool specular = point.w != 0.0f && hp.pathLength > 1.001f * length(hp.position - BUF(params).camera.position);
    vec3 n = octDecode(hp.aovNormal);
    bool sppm = BUF(params).estimator == ESTIMATOR_SPPM;

    float fx = q.x - 0.5f;
    float fy = q.y - 0.5f;
    float x0 = floor(fx);
    float y0 = floor(fy);
    float tx = fx - x0;
    float ty = fy - y0;
    float weights = 0.0f;
    float frames = 0.0f;
    PixelAov a = emptyPixelAov();
    vec4 mean = vec4(0.0f);  // the running mean (not named after its buffer: GLSL would take it for it)
    vec3 direct = vec3(0.0f);
    vec3 radiance[MAP_COUNT];
    float radius[MAP_COUNT];
    float count[MAP_COUNT];
    for (uint m = 0u; m < MAP_COUNT; ++m) {
        radiance[m] = vec3(0.0f);
        radius[m] = 0.0f;
        count[m] = 0.0f;
    }
    for (uint t = 0u; t < 4u; ++t) {
        float x = x0 + float(t & 1u);
        float y = y0 + float(t >> 1u);
        float w = ((t & 1u) != 0u ? tx : 1.0f - tx) * ((t >> 1u) != 0u ? ty : 1.0f - ty);
        if (!(q.z > 0.0f && w > 0.0f && x >= 0.0f && y >= 0.0f && x < float(width) && y < float(height))) {
            continue;  // behind or beside the previous view
        }
        uint s = uint(y) * width + uint(x);
        PixelAov b = BUF(history)[s].aov;
        if (!sawSameSurface(b, point, expected, n, specular)) {
            continue;
        }
        weights += w;
        frames += w * b.frames;
        a.albedo += w * b.albedo;
        a.depth += w * b.depth;
        a.normal += w * b.normal;
        a.coverage += w * b.coverage;
        a.luminance += w * b.luminance;
        a.luminance2 += w * b.luminance2;
        a.background += w * b.background;
        mean += w * BUF(history)[s].accumulation;
        if (sppm) {
            direct += w * BUF(history)[s].sppm.direct;
            for (uint m = 0u; m < MAP_COUNT; ++m) {
                float r = BUF(history)[s].sppm.maps[m].radius;
                vec3 flux = BUF(history)[s].sppm.maps[m].flux;
                radiance[m] += w * (r > 0.0f ? flux * (INV_PI / (b.frames * r * r)) : vec3(0.0f));
                radius[m] += w * r;
                count[m] += w * BUF(history)[s].sppm.count[m];
            }
        }
    }
    if (!(weights > REPROJECT_MIN_WEIGHT)) {
        BUF(aovs)[pixel].frames = 0.0f;  // starts again
        return;
    }
    float inverse = 1.0f / weights;
    float k = clamp(floor(frames * inverse + 0.5f), 1.0f, float(REPROJECT_MAX_FRAMES));
    if (sppm) {
        BUF(sppmPixels)[pixel].direct = direct * inverse;
        for (uint m = 0u; m < MAP_COUNT; ++m) {
            float r = radius[m] * inverse;
            BUF(sppmPixels)[pixel].maps[m].flux = radiance[m] * inverse * (k * PI * r * r);
            BUF(sppmPixels)[pixel].maps[m].radius = r;
            BUF(sppmPixels)[pixel].count[m] = count[m] * inverse;
        }
    }
    BUF(accumulation)[pixel] = mean * inverse;
    a.albedo *= inverse;
    a.normal *= inverse;
    a.coverage *= inverse;
    a.luminance *= inverse;
    a.luminance2 *= inverse;
    a.background *= inverse;
    a.depth *= inverse;
    // The mean depth from where the camera is now: moved by as much as the surface's distance.
    if (point.w != 0.0f) {
        a.depth += hp.pathLength - expected;
    }
    a.frames = k;
    BUF(aovs)[pixel] = a;
}

// STAGE_REPROJECT: pass `pass` (REPROJECT_PASS_*) of one pixel.
PH_FN void reprojectPass(BUF_PARAM uint pixel, uint pass) {
    if (pass == REPROJECT_PASS_SAVE) {
        reprojectSave(BUF_ARG pixel);
    } else {
        reprojectRestore(BUF_ARG pixel);
    }
}

PH_NAMESPACE_END

#endif
