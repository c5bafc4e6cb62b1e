// Heterogeneous media: a medium's coefficients scaled by a density ρ(x) that is constant within
// each voxel of a grid tiling its box. Along a ray every channel's optical depth is σt times one
// number, the density integral D(t) = ∫ ρ, which a walk over the voxels the ray crosses (Amanatides
// & Woo) sums exactly: transmittance is e^(−σt·D) without noise, and a free flight that draws an
// optical depth τ finds where D reaches τ/σt in the same walk ("regular tracking", Sutton et al.
// 1999; exact for piecewise-constant media, where delta and ratio tracking would add noise and
// need a majorant). A homogeneous medium is the grid-less case ρ = 1, D = the length.
#ifndef PHOTON_SHARED_MEDIUM_GRID_H
#define PHOTON_SHARED_MEDIUM_GRID_H

#include "bindings.h"
#include "math.h"

PH_NAMESPACE_BEGIN

// Where a walk along the ray stopped: at t, with the density integral D from its start.
struct DensityWalk {
    float t;
    float integral;
    bool reached;  // D reached the target before the walk's end
};

// Walks the ray o + s·d over s ∈ [t0, t1] (inside md's box) through md's voxels, summing the
// density integral until it reaches `target` (FLOAT_MAX: the whole way). For a homogeneous medium,
// D = s − t0.
PH_FN DensityWalk walkDensity(BUF_PARAM PH_IN(Medium) md, vec3 o, vec3 d, float t0, float t1, float target) {
    DensityWalk w;
    w.t = t1;
    w.integral = t1 - t0;
    w.reached = false;
    if (md.grid == NONE) {
        if (target < w.integral) {
            PH_PRECISE float t = t0 + target;
            w.t = t;
            w.integral = target;
            w.reached = true;
        }
        return w;
    }
    w.integral = 0.0f;
    if (!(t0 < t1)) {
        w.t = t0;
        return w;
    }
    // In voxel units: the box is [0, n], the ray p + s·v.
    vec3 n = vec3(md.resolution);
    vec3 scale = n / (md.upper - md.lower);
    vec3 p = (o - md.lower) * scale;
    vec3 v = d * scale;
    PH_PRECISE vec3 start = p + v * t0;
    ivec3 cell = clamp(ivec3(floor(start)), ivec3(0), ivec3(md.resolution) - ivec3(1));
    ivec3 step = ivec3(v.x >= 0.0f ? 1 : -1, v.y >= 0.0f ? 1 : -1, v.z >= 0.0f ? 1 : -1);
    vec3 inverse = vec3(1.0f) / abs(v);
    vec3 boundary = vec3(cell) + max(vec3(step), vec3(0.0f));
    PH_PRECISE vec3 tNext = vec3(t0) + abs(boundary - start) * inverse;
    vec3 tDelta = inverse;
    float t = t0;
    uint steps = md.resolution.x + md.resolution.y + md.resolution.z;
    for (uint i = 0u; i < steps; ++i) {
        float exit = min(min(min(tNext.x, tNext.y), tNext.z), t1);
        uint voxel = uint(cell.x) + md.resolution.x * (uint(cell.y) + md.resolution.y * uint(cell.z));
        float rho = BUF(densities)[md.grid + voxel];
        PH_PRECISE float gained = rho * (exit - t);
        if (w.integral + gained >= target && rho > 0.0f) {
            PH_PRECISE float at = t + (target - w.integral) / rho;
            w.t = min(at, exit);
            w.integral = target;
            w.reached = true;
            return w;
        }
        PH_PRECISE float sum = w.integral + gained;
        w.integral = sum;
        t = exit;
        if (exit >= t1) {
            break;
        }
        uint axis = tNext.x <= tNext.y && tNext.x <= tNext.z ? 0u : tNext.y <= tNext.z ? 1u : 2u;
        if (axis == 0u) {
            cell.x += step.x;
            tNext.x += tDelta.x;
        } else if (axis == 1u) {
            cell.y += step.y;
            tNext.y += tDelta.y;
        } else {
            cell.z += step.z;
            tNext.z += tDelta.z;
        }
        if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, ivec3(md.resolution)))) {
            break;  // rounding at the box's face
        }
    }
    w.t = t1;
    return w;
}

// D from t0 to t1 along the ray (t1 < t0: minus D from t1 to t0).
PH_FN float densityIntegral(BUF_PARAM PH_IN(Medium) md, vec3 o, vec3 d, float t0, float t1) {
    if (t1 < t0) {
        return -walkDensity(BUF_ARG md, o, d, t1, t0, FLOAT_MAX).integral;
    }
    return walkDensity(BUF_ARG md, o, d, t0, t1, FLOAT_MAX).integral;
}

PH_NAMESPACE_END

#endif
