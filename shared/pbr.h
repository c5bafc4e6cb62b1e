// glTF 2.0's metallic-roughness material (the specification's Appendix B), with
// KHR_materials_transmission, _ior and _volume:
//     f = mix(dielectric, metal, metallic)
//     metal      = F_schlick(baseColor, v·h) · D·Vis                     (conductor_fresnel)
//     dielectric = mix(opaque, transmissive, transmission)
//     opaque     = (1 − F(n·v)) · baseColor/π  +  F(v·h) · D·Vis,  F = F_schlick(F0(ior), ·)
// (the specification's fresnel_mix weights the base by 1 − F(v·h) too; that form reflects up to
// 16% more than it receives at grazing angles, measured by tests/pbr_test.cpp, and 1 − F(n·v)
// keeps every white furnace at or below 1)
//     transmissive = a rough dielectric interface (Walter et al. 2007): reflection with the exact
//                  Fresnel F(v·h, η), refraction (thin-walled: straight through) tinted by baseColor
// with D the GGX distribution of α = roughness², Vis = G/(4|n·l||n·v|) and Smith's separable G.
// A path samples one lobe, picked in proportion to what it roughly reflects seen from ωo, and
// weights the sample by that lobe's f·cos/pdf over the pick's probability: unbiased for any pick
// probabilities, as every lobe's pdf covers its own f. material.h says which lobes paths trace and
// which density estimates read (PBR_TRACED_ALPHA, PBR_DELTA_ALPHA).
#ifndef PHOTON_SHARED_PBR_H
#define PHOTON_SHARED_PBR_H

#include "material.h"
#include "microfacet.h"

PH_NAMESPACE_BEGIN

PH_CONST uint PBR_LOBES_ALL = 0u;     // the whole BSDF
PH_CONST uint PBR_LOBES_TRACED = 1u;  // the lobes eye paths follow by sampling
PH_CONST uint PBR_LOBES_STORED = 2u;  // the lobes density estimates read

// (1 − cosθ)⁵ of Schlick's approximation.
PH_FN float schlickWeight(float cosTheta) {
    float x = 1.0f - clamp(cosTheta, 0.0f, 1.0f);
    float x2 = x * x;
    return x2 * x2 * x;
}

// Schlick's Fresnel F0 + (1 − F0)·w, a lerp that stays uncontracted (portable.h).
PH_FN float schlick(float f0, float w) {
    PH_PRECISE float f = f0 + (1.0f - f0) * w;
    return f;
}

PH_FN vec3 schlickColour(vec3 f0, float w) {
    PH_PRECISE vec3 f = f0 + (vec3(1.0f) - f0) * w;
    return f;
}

// Normal-incidence reflectance of a dielectric of index ior in air (0.04 at 1.5).
PH_FN float dielectricF0(float ior) {
    float r = (ior - 1.0f) / (ior + 1.0f);
    return r * r;
}

PH_FN float meanOf(vec3 c) { return (c.x + c.y + c.z) * (1.0f / 3.0f); }

// What each lobe reflects of light arriving from ωo (cosO = n·ωo), roughly: the pick weights.
struct PbrLobes {
    float diffuse;
    float specular;      // the opaque dielectric's coat
    float metal;
    float transmission;  // the transmissive dielectric: its reflection and refraction together
};

PH_FN PbrLobes pbrLobes(PH_IN(Material) m, float cosO, uint subset) {
    float fw = schlickWeight(cosO);
    float fresnel = schlick(dielectricF0(m.ior), fw);
    float dielectric = 1.0f - m.metallic;
    float opaque = dielectric * (1.0f - m.transmission);
    PbrLobes w;
    w.diffuse = opaque * (1.0f - fresnel) * meanOf(m.albedo);
    w.specular = opaque * fresnel;
    w.metal = m.metallic * meanOf(schlickColour(m.albedo, fw));
    w.transmission = dielectric * m.transmission;
    bool specularTraced = m.roughness < PBR_TRACED_ALPHA;
    if (subset == PBR_LOBES_TRACED) {
        w.diffuse = 0.0f;
    }
    if (subset == PBR_LOBES_STORED) {
        w.transmission = 0.0f;
    }
    if ((subset == PBR_LOBES_TRACED && !specularTraced) || (subset == PBR_LOBES_STORED && specularTraced)) {
        w.specular = 0.0f;
        w.metal = 0.0f;
    }
    return w;
}

PH_FN float pbrLobeSum(PH_IN(PbrLobes) w) { return w.diffuse + w.specular + w.metal + w.transmission; }

// The lobes a shading point may read: the stored ones, or all that shadow rays can find.
PH_FN uint pbrEvaluatedLobes(PH_IN(Material) m) {
    return (m.flags & MATERIAL_FLAG_STORED_PART) != 0u ? PBR_LOBES_STORED : PBR_LOBES_ALL;
}

// Probability that an eye path at this surface follows a traced lobe rather than ending with
// density estimates of the stored ones.
PH_FN float pbrTracedProbability(PH_IN(Material) m, float cosO) {
    float all = pbrLobeSum(pbrLobes(m, cosO, PBR_LOBES_ALL));
    return all > 0.0f ? pbrLobeSum(pbrLobes(m, cosO, PBR_LOBES_TRACED)) / all : 0.0f;
}

// f(ωo, ωi) for ωi on ωo's side (n faces ωo; both cosines positive): the diffuse lobe and the
// reflecting specular lobes that are not delta distributions, as `pbrEvaluatedLobes` allows.
PH_FN vec3 evalPbr(PH_IN(Material) m, vec3 wo, vec3 wi, vec3 n, float cosO, float cosI) {
    vec3 h = unitVector(wi + wo);
    float voh = dot(wo, h);
    float fw = schlickWeight(voh);
    float fresnel = schlick(dielectricF0(m.ior), fw);
    float dielectric = 1.0f - m.metallic;
    float opaque = dielectric * (1.0f - m.transmission);
    PH_PRECISE vec3 f = m.albedo * (opaque * (1.0f - schlick(dielectricF0(m.ior), schlickWeight(cosO))) * INV_PI);
    bool stored = (m.flags & MATERIAL_FLAG_STORED_PART) != 0u;
    bool specularTraced = m.roughness < PBR_TRACED_ALPHA;
    if (m.roughness >= PBR_DELTA_ALPHA && !(stored && specularTraced)) {
        float a = m.roughness;
        float dVis = ggxD(dot(h, n), a) * ggxG1(cosO, a) * ggxG1(cosI, a) / (4.0f * cosO * cosI);
        PH_PRECISE vec3 specular = vec3(opaque * fresnel) + schlickColour(m.albedo, fw) * m.metallic;
        if (!stored) {
            specular = specular + vec3(dielectric * m.transmission * fresnelDielectric(voh, m.ior));
        }
        f = f + specular * dVis;
    }
    return f;
}

// The density of samplePbr's reflected directions (all lobes but transmission's), per solid angle.
PH_FN float pdfPbr(PH_IN(Material) m, vec3 wo, vec3 wi, vec3 n, uint subset) {
    float cosO = dot(wo, n);
    float cosI = dot(wi, n);
    if (cosO <= 0.0f || cosI <= 0.0f) {
        return 0.0f;
    }
    PbrLobes w = pbrLobes(m, cosO, subset);
    float total = pbrLobeSum(w);
    if (!(total > 0.0f)) {
        return 0.0f;
    }
    vec3 h = unitVector(wi + wo);
    float cosH = dot(h, n);
    float voh = dot(wo, h);
    PH_PRECISE float reflectance = w.specular + w.metal;
    if (w.transmission > 0.0f) {
        reflectance = reflectance + w.transmission * fresnelDielectric(voh, m.ior);
    }
    float specular = voh > 0.0f ? ggxD(cosH, m.roughness) * cosH / (4.0f * voh) : 0.0f;
    return (w.diffuse * cosI * INV_PI + reflectance * specular) / total;
}

// Samples ωi from the lobes of `subset`. nf is the shading normal on ωo's side, entering whether
// ωo lies outside the surface (for the index ratio of transmission). Three random numbers.
PH_FN BsdfSample samplePbr(PH_IN(Material) m, vec3 wo, vec3 nf, bool entering, uint subset, float u0, float u1, float u2,
                           PH_OUT(bool) transmits) {
    BsdfSample bs;
    bs.direction = nf;
    bs.weight = vec3(0.0f);
    bs.lobe = LOBE_NONE;
    transmits = false;
    float cosO = dot(wo, nf);
    PbrLobes w = pbrLobes(m, cosO, subset);
    float total = pbrLobeSum(w);
    if (!(total > 0.0f) || !(cosO > 0.0f)) {
        return bs;
    }
    float u = u0 * total;
    float opaque = (1.0f - m.metallic) * (1.0f - m.transmission);
    if (u < w.diffuse) {
        bs.direction = localToWorld(sampleCosineHemisphere(u1, u2), nf);
        bs.weight = m.albedo * (opaque * (1.0f - schlick(dielectricF0(m.ior), schlickWeight(cosO))) * total / w.diffuse);
        bs.lobe = LOBE_DIFFUSE;
        return bs;
    }
    float a = m.roughness;
    vec3 h = localToWorld(sampleGgxNormal(u1, u2, a), nf);
    float voh = dot(wo, h);
    float cosH = dot(h, nf);
    if (!(voh > 0.0f)) {
        return bs;
    }
    uint lobe = a < PBR_TRACED_ALPHA ? LOBE_SPECULAR : LOBE_GLOSSY;
    vec3 wi = reflectAbout(wo, h);
    // f·cosθi / pdf with pdf = D·cosθh / (4|ωo·h|): D cancels, G·(ωo·h)/(cosθo·cosθh) is left.
    if (u < w.diffuse + w.specular + w.metal) {
        float cosI = dot(wi, nf);
        if (!(cosI > 0.0f)) {
            return bs;
        }
        float lobeWeight = ggxG1(cosO, a) * ggxG1(cosI, a) * voh / (cosO * cosH);
        float fw = schlickWeight(voh);
        if (u < w.diffuse + w.specular) {
            bs.weight = vec3(opaque * schlick(dielectricF0(m.ior), fw) * lobeWeight * total / w.specular);
        } else {
            bs.weight = schlickColour(m.albedo, fw) * (m.metallic * lobeWeight * total / w.metal);
        }
        bs.direction = wi;
        bs.lobe = lobe;
        return bs;
    }
    // The transmissive dielectric: reflect with the exact Fresnel of the microfacet, else refract
    // (the weights F/F and (1 − F)/(1 − F) are 1), reusing what is left of u0's interval.
    bool thin = (m.flags & MATERIAL_FLAG_THIN_WALLED) != 0u;
    float eta = entering || thin ? m.ior : 1.0f / m.ior;
    float v = (u - w.diffuse - w.specular - w.metal) / w.transmission;
    float reflectance = fresnelDielectric(voh, eta);
    vec3 tint = vec3(1.0f);
    if (v >= reflectance) {
        if (thin) {
            wi = wi - 2.0f * dot(wi, nf) * nf;  // through a thin sheet: the reflection, mirrored by the sheet
        } else {
            vec3 wt = wi;
            refractThrough(wo, h, eta, wt);  // no total internal reflection here: reflectance < 1
            wi = unitVector(wt);
        }
        tint = m.albedo;
        transmits = true;
    }
    float cosI = abs(dot(wi, nf));
    if (transmits ? dot(wi, nf) >= 0.0f : dot(wi, nf) <= 0.0f) {
        return bs;
    }
    float lobeWeight = ggxG1(cosO, a) * ggxG1(cosI, a) * voh / (cosO * cosH);
    bs.direction = wi;
    bs.weight = tint * ((1.0f - m.metallic) * m.transmission * lobeWeight * total / w.transmission);
    bs.lobe = LOBE_SPECULAR;
    return bs;
}

// Beer–Lambert absorption of a ray that travelled t inside a material with an absorption
// coefficient (KHR_materials_volume), seen where it leaves: from behind the surface it met
// (cosGeometric = ωo·n_g < 0).
PH_FN vec3 volumeTransmittance(PH_IN(Material) m, float cosGeometric, float t) {
    if (cosGeometric >= 0.0f || isBlack(m.attenuation)) {
        return vec3(1.0f);
    }
    vec3 x = m.attenuation * t;
    return vec3(expNegative(x.x), expNegative(x.y), expNegative(x.z));
}

PH_NAMESPACE_END

#endif
