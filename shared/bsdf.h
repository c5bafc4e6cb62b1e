// Materials: Lambertian, mirror, smooth dielectric with exact Fresnel, a glossy BRDF made of a
// Lambertian base plus a GGX microfacet lobe (Walter et al., "Microfacet Models for Refraction
// through Rough Surfaces", EGSR 2007), and glTF's metallic-roughness material (pbr.h). Directions
// point away from the surface.
#ifndef PHOTON_SHARED_BSDF_H
#define PHOTON_SHARED_BSDF_H

#include "material.h"
#include "microfacet.h"
#include "pbr.h"
#include "rng.h"
#include "sampling.h"

PH_NAMESPACE_BEGIN

// f(wo, wi) of the non-specular materials; n faces wo. Zero when wi is below the surface.
PH_FN vec3 evalBsdf(PH_IN(Material) m, vec3 wo, vec3 wi, vec3 n) {
    float cosI = dot(wi, n);
    float cosO = dot(wo, n);
    if (cosI <= 0.0f || cosO <= 0.0f) {
        return vec3(0.0f);
    }
    // The gather evaluates this for every photon: the Lambertian term every type shares (the delta
    // materials and emitters have albedo 0), then a switch with three targets (one that returned
    // from each of the seven cases cost the CUDA gather 14% on an H100, docs/performance.md).
    vec3 f = m.albedo * INV_PI;
    PH_COVERS(MATERIAL_TYPE_COUNT, 7u);
    switch (m.type) {
        case MATERIAL_PBR:
            return evalPbr(m, wo, wi, n, cosO, cosI);
        case MATERIAL_GLOSSY: {
            vec3 h = unitVector(wi + wo);
            float alpha = m.roughness;
            float g = ggxG1(cosO, alpha) * ggxG1(cosI, alpha);
            f += m.specular * (ggxD(dot(h, n), alpha) * g / (4.0f * cosO * cosI));
            break;
        }
        case MATERIAL_DIFFUSE:
        case MATERIAL_REFLECTIVE:  // the Lambertian base under the coat
        case MATERIAL_MIRROR:      // deltas and emitters: albedo 0, nothing to evaluate
        case MATERIAL_GLASS:
        case MATERIAL_EMITTER:
            break;
    }
    return f;
}

// The mirror coat of a reflective material (nf: the shading normal on wo's side): its mirror
// direction, weighted by 1 / the probability of choosing it.
PH_FN BsdfSample sampleMirrorCoat(PH_IN(Material) m, vec3 wo, vec3 nf) {
    BsdfSample bs;
    bs.direction = reflectAbout(wo, nf);
    bs.weight = m.specular / specularLobeProbability(m);
    bs.lobe = LOBE_SPECULAR;
    return bs;
}

// A sample on the wrong side of the geometric surface (n, and side: which side of it wo is on) is
// absorbed, so that no light leaks through where the shading and geometric normals differ: a
// reflection must stay on wo's side, a transmission must cross.
PH_FN BsdfSample absorbAcrossSurface(PH_IN(BsdfSample) proposed, vec3 n, float side, bool transmits) {
    BsdfSample bs = proposed;
    float across = dot(bs.direction, n) * side;  // > 0: the side wo came from
    if (bs.lobe != LOBE_NONE && (transmits ? across >= 0.0f : across <= 0.0f)) {
        bs.lobe = LOBE_NONE;
        bs.weight = vec3(0.0f);
    }
    return bs;
}

// Sample wi given wo. n is the geometric normal as the primitive defines it (outward for
// spheres): the dielectric needs it to tell entering from leaving. ns is the shading normal, on
// n's side, about which the lobes are sampled; a direction on the wrong side of the geometric
// surface (possible where the two normals differ) is absorbed, so that no light leaks through it.
// pbrSubset: the PBR_LOBES_* a glTF material samples from. Uses three random numbers.
PH_FN BsdfSample sampleBsdfLobes(PH_IN(Material) m, vec3 wo, vec3 n, vec3 ns, uint pbrSubset, PH_INOUT(Rng) rng) {
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
    PH_COVERS(MATERIAL_TYPE_COUNT, 7u);
    switch (m.type) {
        case MATERIAL_DIFFUSE:
            bs.direction = localToWorld(sampleCosineHemisphere(u1, u2), nf);
            bs.weight = m.albedo;
            bs.lobe = LOBE_DIFFUSE;
            break;
        case MATERIAL_GLOSSY: {
            float pSpecular = specularLobeProbability(m);
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
            break;
        }
        case MATERIAL_MIRROR:
            bs.direction = reflectAbout(wo, nf);
            bs.weight = m.specular;
            bs.lobe = LOBE_SPECULAR;
            break;
        case MATERIAL_REFLECTIVE: {
            float pMirror = specularLobeProbability(m);
            if (u0 < pMirror) {
                bs = sampleMirrorCoat(m, wo, nf);
            } else {
                bs.direction = localToWorld(sampleCosineHemisphere(u1, u2), nf);
                bs.weight = m.albedo / (1.0f - pMirror);
                bs.lobe = LOBE_DIFFUSE;
            }
            break;
        }
        case MATERIAL_GLASS: {
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
            break;
        }
        case MATERIAL_PBR:
            bs = samplePbr(m, wo, nf, side > 0.0f, pbrSubset, u0, u1, u2, transmits);
            break;
        case MATERIAL_EMITTER:
            break;  // absorbs everything
    }
    return absorbAcrossSurface(bs, n, side, transmits);
}

// The density per solid angle with which sampleBsdf draws wi, over the directions on wo's side
// (n: the shading normal facing wo). With evalBsdf it makes the BSDF one strategy of multiple
// importance sampling; the delta lobes of mirrors and glass have no density, so 0 for them.
PH_FN float pdfBsdf(PH_IN(Material) m, vec3 wo, vec3 wi, vec3 n) {
    float cosI = dot(wi, n);
    float cosO = dot(wo, n);
    if (cosI <= 0.0f || cosO <= 0.0f) {
        return 0.0f;
    }
    PH_COVERS(MATERIAL_TYPE_COUNT, 7u);
    switch (m.type) {
        case MATERIAL_DIFFUSE:
            return cosI * INV_PI;
        case MATERIAL_GLOSSY: {
            float pSpecular = specularLobeProbability(m);
            vec3 h = unitVector(wi + wo);
            float cosH = dot(h, n);
            float specular = ggxD(cosH, m.roughness) * cosH / (4.0f * dot(wo, h));
            return pSpecular * specular + (1.0f - pSpecular) * cosI * INV_PI;
        }
        case MATERIAL_REFLECTIVE:
            return (1.0f - specularLobeProbability(m)) * cosI * INV_PI;  // the base under the coat
        case MATERIAL_PBR:
            return pdfPbr(m, wo, wi, n, pbrEvaluatedLobes(m));
        case MATERIAL_MIRROR:
        case MATERIAL_GLASS:
        case MATERIAL_EMITTER:
            break;
    }
    return 0.0f;
}

// Sample wi from everything the material does (the stored lobes alone for a storedPart()).
PH_FN BsdfSample sampleBsdf(PH_IN(Material) m, vec3 wo, vec3 n, vec3 ns, PH_INOUT(Rng) rng) {
    return sampleBsdfLobes(m, wo, n, ns, pbrEvaluatedLobes(m), rng);
}

PH_NAMESPACE_END

#endif
