// Both ways light goes at a smooth dielectric, each with its share, for eye paths that follow
// both (eye_trace.h) as Whitted's and Jensen's ray tracers do: the reflection weighted by the
// Fresnel reflectance F, the refraction by 1 - F times the glass's tint. sampleBsdf picks one of
// them with probability F instead, at weight 1: unbiased, but a pixel whose reflection sees black
// in one frame in twenty is salt and pepper that frames average away slowly.
#ifndef PHOTON_SHARED_SPECULAR_SPLIT_H
#define PHOTON_SHARED_SPECULAR_SPLIT_H

#include "dispersion.h"

PH_NAMESPACE_BEGIN

struct SpecularSplit {
    BsdfSample reflected;
    BsdfSample transmitted;    // LOBE_NONE under total internal reflection
    uint transmittedChannel;   // the CHANNEL_* the refracted branch carries
};

// Glass m (after meetDispersion) met from wo; n the geometric normal as the primitive defines it,
// ns the shading normal, as sampleBsdf takes them. A path that carries the frame's three
// wavelengths into dispersive glass reflects all three, each by its own F, and refracts one,
// drawn as sampleDispersiveGlass draws it (one draw); otherwise no draw.
PH_FN SpecularSplit splitDielectric(BUF_PARAM PH_IN(Material) m, vec3 wo, vec3 n, vec3 ns, uint channel,
                                    PH_INOUT(Rng) rng) {
    float side = dot(wo, n) >= 0.0f ? 1.0f : -1.0f;
    vec3 nf = ns * side;
    bool entering = side > 0.0f;
    SpecularSplit split;
    split.transmittedChannel = channel;
    split.reflected.direction = reflectAbout(wo, nf);
    split.reflected.lobe = LOBE_SPECULAR;
    split.transmitted.direction = nf;
    split.transmitted.weight = vec3(0.0f);
    split.transmitted.lobe = LOBE_NONE;
    float ior = m.ior;
    vec3 reflectance;
    if (channel == CHANNEL_ALL && disperses(BUF_ARG m)) {
        for (uint i = 0u; i < 3u; ++i) {
            float iorI = dispersedIor(BUF_ARG m, i);
            reflectance[i] = fresnelDielectric(dot(wo, nf), entering ? iorI : 1.0f / iorI);
        }
        // Wavelength j with probability (1 - F_j) / Σ(1 - F_k), at weight 3 (1 - mean F): the
        // refraction's share, as sampleDispersiveGlass keeps it.
        vec3 transmittance = vec3(1.0f) - reflectance;
        float total = transmittance.x + transmittance.y + transmittance.z;
        if (total > 0.0f) {
            float pick = rngNext(rng) * total;
            uint j = pick < transmittance.x ? 0u : (pick < transmittance.x + transmittance.y ? 1u : 2u);
            if (transmittance[j] <= 0.0f) {
                j = transmittance.y > 0.0f ? 1u : (transmittance.x > 0.0f ? 0u : 2u);
            }
            ior = dispersedIor(BUF_ARG m, j);
            split.transmittedChannel = j;
            split.transmitted.weight = onlyChannel(m.specular, j, total);
        }
    } else {
        float f = fresnelDielectric(dot(wo, nf), entering ? m.ior : 1.0f / m.ior);
        reflectance = vec3(f);
        split.transmitted.weight = m.specular * (1.0f - f);
    }
    split.reflected.weight = reflectance;
    vec3 wt = nf;
    if (!isBlack(split.transmitted.weight) && refractThrough(wo, nf, entering ? ior : 1.0f / ior, wt)) {
        split.transmitted.direction = unitVector(wt);
        split.transmitted.lobe = LOBE_SPECULAR;
    }
    split.reflected = absorbAcrossSurface(split.reflected, n, side, false);
    split.transmitted = absorbAcrossSurface(split.transmitted, n, side, true);
    return split;
}

PH_NAMESPACE_END

#endif
