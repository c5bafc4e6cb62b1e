// The reproject stage: temporal reprojection (as in SVGF, Schied et al., HPG 2017) of a photon
// mapper's per-pixel history. When the camera has moved since the frame before (FLAG_REPROJECT),
// each pixel takes over the means of the pixels that saw its surface then, instead of starting
// again. Its passes, one dispatch each:
//   save     every pixel's means (sppm's statistics, the running mean, the auxiliary images) set
//            aside into `history`, so that the next pass reads the frame before's whatever order
//            pixels run in;
//   restore  where the pixel's surface appears now ("motion from depth": its depth along the ray
//            through the pixel's centre) projected into the previous camera, and the histories of
//            the pixels about that point that saw the same surface, interpolated (Catmull-Rom,
//            or bilinearly by an edge): each one's mean depth within REPROJECT_DEPTH_TOLERANCE of the point's distance from
//            the previous camera and its mean normal's direction within acos(REPROJECT_NORMAL_COS)
//            of the point's. Where none did (the surface came into view, or another surface was
//            there) the pixel starts again (history.h: zero frames).
// The depth is the path's length through mirrors and glass (aov.h), so what a mirror shows moves
// as its virtual image does. Each carried history counts at most REPROJECT_MAX_FRAMES frames, so
// that what each move's interpolation smears gives way to new frames.
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
        for (uint m = 0u; m < SURFACE_MAP_COUNT; ++m) {
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
    bool sameDepth = specular || abs(before.depth - expected) <= REPROJECT_DEPTH_TOLERANCE * expected;
    bool sameNormal = specular || dot(before.normal, n) >= REPROJECT_NORMAL_COS * length(before.normal);
    return sameDepth && sameNormal;
}

// Catmull-Rom's weights of the four taps at -1, 0, 1, 2 about a point t ∈ [0, 1) past tap 0.
PH_FN vec4 catmullRomWeights(float t) {
    float t2 = t * t;
    float t3 = t2 * t;
    return 0.5f * vec4(-t + 2.0f * t2 - t3, 2.0f - 5.0f * t2 + 3.0f * t3, t + 4.0f * t2 - 3.0f * t3, t3 - t2);
}

// Pass restore of one pixel: the histories of the pixels of the frame before about where its
// surface appeared then, interpolated. Where all 4 × 4 about that point saw the same surface,
// by Catmull-Rom (as temporal antialiasing resamples its history: a moving camera resamples every
// frame, and bilinear weights would blur the image by a little more each time, until after a few
// dozen moves its edges, shadows and caustics were smeared); elsewhere (edges, where some saw
// another surface) bilinearly from the 2 × 2 that did (SVGF's rule). Means are interpolated as
// they are; sppm's statistics as the radiance they give, τ / (k π R²), with R and N, from which τ
// is made again for the carried frame count k: a photon mapper's radius, count and flux do not
// interpolate, but the estimate they hold does.
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
    // pixel the ray went, so neither its depth nor its normal tells whether the history is its
    // own: any history that saw a surface is taken (measured: held to a 25% depth tolerance, the
    // glass ball's pixels started again so often that the image there was one frame's).
    bool specular = point.w != 0.0f && hp.pathLength > 1.001f * length(hp.position - BUF(params).camera.position);
    vec3 n = octDecode(hp.aovNormal);
    bool sppm = BUF(params).estimator == ESTIMATOR_SPPM;

    float fx = q.x - 0.5f;
    float fy = q.y - 0.5f;
    float x0 = floor(fx);
    float y0 = floor(fy);
    float tx = fx - x0;
    float ty = fy - y0;
    bool everyTap = q.z > 0.0f;
    for (uint t = 0u; t < 16u && everyTap; ++t) {
        float x = x0 - 1.0f + float(t & 3u);
        float y = y0 - 1.0f + float(t >> 2u);
        everyTap = x >= 0.0f && y >= 0.0f && x < float(width) && y < float(height) &&
                   sawSameSurface(BUF(history)[uint(y) * width + uint(x)].aov, point, expected, n, specular);
    }
    vec4 wx = catmullRomWeights(tx);
    vec4 wy = catmullRomWeights(ty);
    float weights = 0.0f;
    float frames = 0.0f;
    PixelAov a = emptyPixelAov();
    vec4 mean = vec4(0.0f);  // the running mean (not named after its buffer: GLSL would take it for it)
    vec3 direct = vec3(0.0f);
    vec3 radiance[SURFACE_MAP_COUNT];
    float radius[SURFACE_MAP_COUNT];
    float count[SURFACE_MAP_COUNT];
    for (uint m = 0u; m < SURFACE_MAP_COUNT; ++m) {
        radiance[m] = vec3(0.0f);
        radius[m] = 0.0f;
        count[m] = 0.0f;
    }
    for (uint t = 0u; t < 16u; ++t) {
        uint i = t & 3u;
        uint j = t >> 2u;
        float x = x0 - 1.0f + float(i);
        float y = y0 - 1.0f + float(j);
        float w = wx[i] * wy[j];
        if (!everyTap) {
            bool inner = i == 1u || i == 2u;
            inner = inner && (j == 1u || j == 2u);
            w = inner ? (i == 2u ? tx : 1.0f - tx) * (j == 2u ? ty : 1.0f - ty) : 0.0f;
        }
        if (!(q.z > 0.0f && w != 0.0f && x >= 0.0f && y >= 0.0f && x < float(width) && y < float(height))) {
            continue;  // behind or beside the previous view
        }
        uint s = uint(y) * width + uint(x);
        PixelAov b = BUF(history)[s].aov;
        if (!everyTap && !sawSameSurface(b, point, expected, n, specular)) {
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
            for (uint m = 0u; m < SURFACE_MAP_COUNT; ++m) {
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
    // Catmull-Rom's negative lobes can overshoot below zero beside an edge of light.
    if (sppm) {
        BUF(sppmPixels)[pixel].direct = max(direct * inverse, vec3(0.0f));
        for (uint m = 0u; m < SURFACE_MAP_COUNT; ++m) {
            float r = max(radius[m] * inverse, 0.0f);
            BUF(sppmPixels)[pixel].maps[m].flux = max(radiance[m] * inverse, vec3(0.0f)) * (k * PI * r * r);
            BUF(sppmPixels)[pixel].maps[m].radius = r;
            BUF(sppmPixels)[pixel].count[m] = max(count[m] * inverse, 0.0f);
        }
    }
    BUF(accumulation)[pixel] = max(mean * inverse, vec4(0.0f));
    a.albedo = max(a.albedo * inverse, vec3(0.0f));
    a.normal *= inverse;
    a.coverage = clamp(a.coverage * inverse, 0.0f, 1.0f);
    a.luminance = max(a.luminance * inverse, 0.0f);
    a.luminance2 = max(a.luminance2 * inverse, a.luminance * a.luminance);
    a.background = max(a.background * inverse, vec3(0.0f));
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
