// Small vector helpers. Everything here is +, -, *, /, sqrt and comparisons, so that results are
// identical on every IEEE backend (see portable.h).
#ifndef PHOTON_SHARED_MATH_H
#define PHOTON_SHARED_MATH_H

#include "constants.h"

PH_NAMESPACE_BEGIN

PH_FN float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

PH_FN float lengthSquared(vec3 v) { return dot(v, v); }

PH_FN vec3 unitVector(vec3 v) { return v * (1.0f / sqrt(dot(v, v))); }

PH_FN bool isBlack(vec3 c) { return c.x <= 0.0f && c.y <= 0.0f && c.z <= 0.0f; }

PH_FN float signNotZero(float x) { return x >= 0.0f ? 1.0f : -1.0f; }

// 1 - cos(angle between unit vectors a and b), accurate for tiny angles where the cosine
// itself rounds to 1: |a - b|² = 2 - 2cos.
PH_FN float oneMinusCos(vec3 a, vec3 b) {
    vec3 d = a - b;
    return 0.5f * dot(d, d);
}

// sin(2πu) and cos(2πu) by reduction to [-π/4, π/4] and Taylor polynomials (|error| < 4e-7).
// Used instead of sin/cos wherever the result steers a photon or a ray, see portable.h.
PH_FN void sinCos2Pi(float u, PH_OUT(float) s, PH_OUT(float) c) {
    float t = 4.0f * u;
    float q = floor(t + 0.5f);
    float a = (t - q) * (0.5f * PI);
    float a2 = a * a;
    float sa = a * (1.0f + a2 * (-1.6666667e-1f + a2 * (8.3333333e-3f + a2 * (-1.9841270e-4f + a2 * 2.7557319e-6f))));
    float ca = 1.0f + a2 * (-0.5f + a2 * (4.1666667e-2f + a2 * (-1.3888889e-3f + a2 * 2.4801587e-5f)));
    uint quadrant = uint(int(q)) & 3u;
    if (quadrant == 0u) {
        s = sa;
        c = ca;
    } else if (quadrant == 1u) {
        s = ca;
        c = -sa;
    } else if (quadrant == 2u) {
        s = -sa;
        c = -ca;
    } else {
        s = -ca;
        c = sa;
    }
}

// atan2(y, x) in [−π, π], reduced to atan of a ratio in [0, 1] and an odd polynomial there
// (Abramowitz & Stegun 4.4.49's form, |error| < 2e-6 rad), for the same reason as sinCos2Pi: the
// texel a direction looks up must be the same on every backend. 0 for (0, 0).
PH_FN float atan2Poly(float y, float x) {
    float ax = abs(x);
    float ay = abs(y);
    float hi = max(ax, ay);
    if (!(hi > 0.0f)) {
        return 0.0f;
    }
    float a = min(ax, ay) / hi;
    float s = a * a;
    float r = a * (0.99997726f + s * (-0.33262347f + s * (0.19354346f + s * (-0.11643287f + s * (0.05265332f + s * -0.01172120f)))));
    if (ay > ax) {
        r = 0.5f * PI - r;
    }
    if (x < 0.0f) {
        r = PI - r;
    }
    return y < 0.0f ? -r : r;
}

// e^(−x) for x ≥ 0 without a transcendental function, so that every backend computes the same
// bits (libm's, CUDA's and the drivers' exp differ): e^(−x) = 2^(−k) · e^(−f·ln 2) with k = ⌊x·log₂e⌋,
// the power of two written into the exponent field and the rest a Taylor polynomial
// (relative error < 2e-7).
PH_FN float expNegative(float x) {
    float y = max(x, 0.0f) * 1.44269504f;
    if (!(y < 126.0f)) {
        return 0.0f;
    }
    float k = floor(y);
    float t = (y - k) * 0.693147181f;
    float p = 1.0f - t * (1.0f - t * (0.5f - t * (1.6666667e-1f - t * (4.1666667e-2f - t * (8.3333333e-3f -
              t * (1.3888889e-3f - t * (1.9841270e-4f - t * 2.4801587e-5f)))))));
    return p * uintBitsToFloat(uint(127 - int(k)) << 23u);
}

// Orthonormal basis around a unit normal (Duff et al., "Building an Orthonormal Basis, Revisited",
// JCGT 2017). localToWorld maps (x, y, z) in that frame, z along n, to world space.
PH_FN vec3 localToWorld(vec3 v, vec3 n) {
    float sgn = signNotZero(n.z);
    float a = -1.0f / (sgn + n.z);
    float b = n.x * n.y * a;
    vec3 t = vec3(1.0f + sgn * n.x * n.x * a, sgn * b, -sgn * n.x);
    vec3 bt = vec3(b, sgn + n.y * n.y * a, -n.y);
    return v.x * t + v.y * bt + v.z * n;
}

// A direction built from its angle to an axis, given as x = 1 - cosθ (precise for narrow cones),
// and an azimuth u ∈ [0, 1).
PH_FN vec3 directionAroundAxis(vec3 axis, float x, float u) {
    float cosTheta = 1.0f - x;
    float sinTheta = sqrt(max(0.0f, x * (2.0f - x)));
    float s;
    float c;
    sinCos2Pi(u, s, c);
    return localToWorld(vec3(c * sinTheta, s * sinTheta, cosTheta), axis);
}

// Octahedral encoding of unit vectors into 2 × 16 bits (Cigolle et al., JCGT 2014). Each
// coordinate maps [-1, 1] to 0..65534, so that 0 and ±1 (the axes) are exact.
PH_FN uint quantizeSnorm16(float x) { return uint(floor(clamp(x, -1.0f, 1.0f) * 32767.0f + 32767.5f)); }

PH_FN float dequantizeSnorm16(uint q) { return (float(q) - 32767.0f) * (1.0f / 32767.0f); }

PH_FN uint octEncode(vec3 n) {
    float l1 = abs(n.x) + abs(n.y) + abs(n.z);
    float px = n.x / l1;
    float py = n.y / l1;
    if (n.z < 0.0f) {
        float wx = (1.0f - abs(py)) * signNotZero(px);
        float wy = (1.0f - abs(px)) * signNotZero(py);
        px = wx;
        py = wy;
    }
    return quantizeSnorm16(px) | (quantizeSnorm16(py) << 16u);
}

// The decoded direction before normalisation: enough to tell which side of a surface it is on.
PH_FN vec3 octDecodeUnnormalized(uint e) {
    float px = dequantizeSnorm16(e & 0xffffu);
    float py = dequantizeSnorm16(e >> 16u);
    vec3 n = vec3(px, py, 1.0f - abs(px) - abs(py));
    float t = max(-n.z, 0.0f);
    n.x += n.x >= 0.0f ? -t : t;
    n.y += n.y >= 0.0f ? -t : t;
    return n;
}

PH_FN vec3 octDecode(uint e) { return unitVector(octDecodeUnnormalized(e)); }

// Start a new ray at a surface point without hitting that surface again: step off the surface
// on the side the ray leaves to, by a distance relative to the coordinates' magnitude.
PH_FN vec3 offsetRayOrigin(vec3 p, vec3 geometricNormal, vec3 direction) {
    float scale = max(1.0f, maxComponent(abs(p)));
    float side = dot(direction, geometricNormal) >= 0.0f ? 1.0f : -1.0f;
    return p + geometricNormal * (side * 1.0e-4f * scale);
}

// Whether every component is a finite number (NaN compares false).
PH_FN bool isFinite(vec3 v) { return abs(v.x) <= FLOAT_MAX && abs(v.y) <= FLOAT_MAX && abs(v.z) <= FLOAT_MAX; }

// Rec. 709 luminance of linear RGB.
PH_FN float luminanceOf(vec3 rgb) { return dot(rgb, vec3(0.2126f, 0.7152f, 0.0722f)); }

PH_NAMESPACE_END

#endif
