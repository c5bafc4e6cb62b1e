// The pieces every BSDF is made of: sampled directions and their weights, exact dielectric
// Fresnel, mirror and Snell directions, and the GGX (Trowbridge–Reitz) microfacet distribution with
// Smith masking (Walter et al., "Microfacet Models for Refraction through Rough Surfaces", EGSR
// 2007). Directions point away from the surface.
#ifndef PHOTON_SHARED_MICROFACET_H
#define PHOTON_SHARED_MICROFACET_H

#include "math.h"
#include "sampling.h"

PH_NAMESPACE_BEGIN

PH_CONST uint LOBE_NONE = 0u;      // absorbed
PH_CONST uint LOBE_DIFFUSE = 1u;   // Lambertian
PH_CONST uint LOBE_GLOSSY = 2u;    // the GGX microfacet lobe
PH_CONST uint LOBE_SPECULAR = 3u;  // mirror or glass: a delta distribution

struct BsdfSample {
    vec3 direction;
    vec3 weight;  // f·|cosθ| / pdf, so that throughput *= weight
    uint lobe;
};

// Fresnel reflectance of a smooth dielectric for unpolarised light. cosI > 0 on the incident side,
// eta = ηt/ηi. Returns 1 under total internal reflection.
PH_FN float fresnelDielectric(float cosI, float eta) {
    float sin2T = (1.0f - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0f) {
        return 1.0f;
    }
    float cosT = sqrt(1.0f - sin2T);
    float rs = (cosI - eta * cosT) / (cosI + eta * cosT);
    float rp = (eta * cosI - cosT) / (eta * cosI + cosT);
    return 0.5f * (rs * rs + rp * rp);
}

// Mirror direction of wo about n.
PH_FN vec3 reflectAbout(vec3 wo, vec3 n) { return 2.0f * dot(wo, n) * n - wo; }

// Snell refraction of wo (on n's side) into a medium eta = ηt/ηi times denser. False under TIR.
PH_FN bool refractThrough(vec3 wo, vec3 n, float eta, PH_OUT(vec3) wt) {
    float cosI = dot(wo, n);
    float sin2T = (1.0f - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0f) {
        return false;
    }
    float cosT = sqrt(1.0f - sin2T);
    wt = -wo / eta + (cosI / eta - cosT) * n;
    return true;
}

// GGX normal distribution D(h) for cosθh = n·h and roughness α.
PH_FN float ggxD(float cosH, float alpha) {
    float a2 = alpha * alpha;
    PH_PRECISE float d = cosH * cosH * (a2 - 1.0f) + 1.0f;  // a lerp: see portable.h
    return a2 / (PI * d * d);
}

// Smith masking G1 for GGX.
PH_FN float ggxG1(float cosV, float alpha) {
    float a2 = alpha * alpha;
    return 2.0f * cosV / (cosV + sqrt(a2 + (1.0f - a2) * cosV * cosV));
}

// A microfacet normal (local frame, z up) with density D(h)·cosθh.
PH_FN vec3 sampleGgxNormal(float u1, float u2, float alpha) {
    float tan2 = alpha * alpha * u1 / (1.0f - u1);
    float cosTheta = 1.0f / sqrt(1.0f + tan2);
    float sinTheta = sqrt(max(0.0f, 1.0f - cosTheta * cosTheta));
    float s;
    float c;
    sinCos2Pi(u2, s, c);
    return vec3(sinTheta * c, sinTheta * s, cosTheta);
}

// The normal on the side of wo.
PH_FN vec3 facingNormal(vec3 n, vec3 wo) { return dot(n, wo) >= 0.0f ? n : -n; }

PH_NAMESPACE_END

#endif
