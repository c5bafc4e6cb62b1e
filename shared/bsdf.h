// Materials: Lambertian, mirror, smooth dielectric with exact Fresnel, and a glossy BRDF made of a
// Lambertian base plus a GGX microfacet lobe (Walter et al., "Microfacet Models for Refraction
// through Rough Surfaces", EGSR 2007). Directions point away from the surface.
#ifndef PHOTON_SHARED_BSDF_H
#define PHOTON_SHARED_BSDF_H

#include "material.h"
#include "rng.h"
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

// f(wo, wi) of the non-specular materials; n faces wo. Zero when wi is below the surface.
PH_FN vec3 evalBsdf(PH_IN(Material) m, vec3 wo, vec3 wi, vec3 n) {
    float cosI = dot(wi, n);
    float cosO = dot(wo, n);
    if (cosI <= 0.0f || cosO <= 0.0f) {
        return vec3(0.0f);
    }
    vec3 f = m.albedo * INV_PI;
    if (m.type == MATERIAL_GLOSSY) {
        vec3 h = unitVector(wi + wo);
        float alpha = m.roughness;
        float g = ggxG1(cosO, alpha) * ggxG1(cosI, alpha);
        f += m.specular * (ggxD(dot(h, n), alpha) * g / (4.0f * cosO * cosI));
    }
    return f;
}

// Probability of picking the GGX lobe of a glossy material.
PH_FN float glossySpecularProbability(PH_IN(Material) m) {
    float d = maxComponent(m.albedo);
    float s = maxComponent(m.specular);
    return (d + s) > 0.0f ? s / (d + s) : 0.0f;
}

// Sample wi given wo. n is the geometric normal as the primitive defines it (outward for
// spheres): the dielectric needs it to tell entering from leaving. ns is the shading normal, on
// n's side, about which the lobes are sampled; a direction on the wrong side of the geometric
// surface (possible where the two normals differ) is absorbed, so that no light leaks through it.
// Uses three random numbers.
PH_FN BsdfSample sampleBsdf(PH_IN(Material) m, vec3 wo, vec3 n, vec3 ns, PH_INOUT(Rng) rng) {
    BsdfSample bs;
    bs.direction = n;
    bs.weight = vec3(0.0f);
    bs.lobe = LOBE_NONE;
    float u0 = rngNext(rng);
    float u1 = rngNext(rng);
    float u2 = rngNext(rng);
    float side = dot(wo, n) >= 0.0f ? 1.0f : -1.0f;
    vec3 nf = ns * side;
    bool transmits = false;
    if (m.type == MATERIAL_DIFFUSE) {
        bs.direction = localToWorld(sampleCosineHemisphere(u1, u2), nf);
        bs.weight = m.albedo;
        bs.lobe = LOBE_DIFFUSE;
    } else if (m.type == MATERIAL_GLOSSY) {
        float pSpecular = glossySpecularProbability(m);
        if (u0 < pSpecular) {
            vec3 h = localToWorld(sampleGgxNormal(u1, u2, m.roughness), nf);
            vec3 wi = reflectAbout(wo, h);
            float cosI = dot(wi, nf);
            float cosO = dot(wo, nf);
            if (cosI > 0.0f && cosO > 0.0f) {
                // f·cosθi / pdf with pdf = D·cosθh / (4|wo·h|): D cancels.
                float alpha = m.roughness;
                float g = ggxG1(cosO, alpha) * ggxG1(cosI, alpha);
                bs.direction = wi;
                bs.weight = m.specular * (g * dot(wo, h) / (cosO * dot(h, nf) * pSpecular));
                bs.lobe = LOBE_GLOSSY;
            }
        } else {
            bs.direction = localToWorld(sampleCosineHemisphere(u1, u2), nf);
            bs.weight = m.albedo / (1.0f - pSpecular);
            bs.lobe = LOBE_DIFFUSE;
        }
    } else if (m.type == MATERIAL_MIRROR) {
        bs.direction = reflectAbout(wo, nf);
        bs.weight = m.specular;
        bs.lobe = LOBE_SPECULAR;
    } else if (m.type == MATERIAL_REFLECTIVE) {
        float pMirror = mirrorCoatProbability(m);
        if (u0 < pMirror) {
            bs.direction = reflectAbout(wo, nf);
            bs.weight = m.specular / pMirror;
            bs.lobe = LOBE_SPECULAR;
        } else {
            bs.direction = localToWorld(sampleCosineHemisphere(u1, u2), nf);
            bs.weight = m.albedo / (1.0f - pMirror);
            bs.lobe = LOBE_DIFFUSE;
        }
    } else if (m.type == MATERIAL_GLASS) {
        bool entering = side > 0.0f;
        float eta = entering ? m.ior : 1.0f / m.ior;
        float reflectance = fresnelDielectric(dot(wo, nf), eta);
        vec3 wt = nf;
        bool refracts = refractThrough(wo, nf, eta, wt);
        // Choose reflection with probability F: the weights F/F and (1-F)/(1-F) are 1.
        if (!refracts || u0 < reflectance) {
            bs.direction = reflectAbout(wo, nf);
            bs.weight = vec3(1.0f);
        } else {
            bs.direction = unitVector(wt);
            bs.weight = m.specular;
            transmits = true;
        }
        bs.lobe = LOBE_SPECULAR;
    }
    float across = dot(bs.direction, n) * side;  // > 0: the side wo came from
    if (bs.lobe != LOBE_NONE && (transmits ? across >= 0.0f : across <= 0.0f)) {
        bs.lobe = LOBE_NONE;
        bs.weight = vec3(0.0f);
    }
    return bs;
}

PH_NAMESPACE_END

#endif
