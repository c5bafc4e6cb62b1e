// Sampling routines. Each takes uniform numbers in [0, 1) and returns a direction or point with
// a known density; the densities are checked by χ² tests in tests/shared_sampling_test.cpp.
#ifndef PHOTON_SHARED_SAMPLING_H
#define PHOTON_SHARED_SAMPLING_H

#include "math.h"

PH_NAMESPACE_BEGIN

// Cosine-weighted hemisphere about +z (Malley's method: project a uniform disk point up).
// Density cosθ/π.
PH_FN vec3 sampleCosineHemisphere(float u1, float u2) {
    float r = sqrt(u1);
    float s;
    float c;
    sinCos2Pi(u2, s, c);
    return vec3(r * c, r * s, sqrt(max(0.0f, 1.0f - u1)));
}

// Uniform direction on the unit sphere. Density 1/4π.
PH_FN vec3 sampleUniformSphere(float u1, float u2) {
    float z = 1.0f - 2.0f * u1;
    float r = sqrt(max(0.0f, 1.0f - z * z));
    float s;
    float c;
    sinCos2Pi(u2, s, c);
    return vec3(r * c, r * s, z);
}

// Uniform direction in the cone about `axis` whose half-angle has 1 - cos = coneX (2: the whole
// sphere). Density 1 / (2π coneX).
PH_FN vec3 sampleUniformCone(vec3 axis, float coneX, float u1, float u2) {
    return directionAroundAxis(axis, u1 * coneX, u2);
}

PH_FN float uniformConePdf(float coneX) { return 1.0f / (TWO_PI * coneX); }

// Uniform point in the unit disk, returned as (x, y). Density 1/π.
PH_FN vec2 sampleUniformDisk(float u1, float u2) {
    float r = sqrt(u1);
    float s;
    float c;
    sinCos2Pi(u2, s, c);
    return vec2(r * c, r * s);
}

// 1 - cos of the half-angle of the cone from `origin` that just holds the sphere (center,
// radius); 2 when the origin is inside it. Written with sin² to stay exact for distant spheres.
PH_FN float sphereConeX(vec3 origin, vec3 center, float radius) {
    float d2 = lengthSquared(center - origin);
    float r2 = radius * radius;
    if (d2 <= r2) {
        return 2.0f;
    }
    float sin2 = r2 / d2;
    float cosMax = sqrt(1.0f - sin2);
    return sin2 / (1.0f + cosMax);
}

// Veach's power heuristic (β = 2) for a sample drawn with density pa when pb is the density of
// the other strategy: pa² / (pa² + pb²), written as a ratio so that large densities do not
// overflow.
PH_FN float powerHeuristic(float pa, float pb) {
    if (!(pa > 0.0f)) {
        return 0.0f;
    }
    float r = pb / pa;
    return 1.0f / (1.0f + r * r);
}

PH_NAMESPACE_END

#endif
