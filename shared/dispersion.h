// Dispersion under spectral rendering (spectral.h): a material whose index of refraction depends
// on the wavelength (KHR_materials_dispersion: n(λ) = n_d + (n_d - 1) · dispersion · cauchy(λ)).
// A path that carries the frame's three wavelengths can follow only one direction where they
// would part, so at a refraction it keeps one of them, at three times its weight (pbrt-v4's
// TerminateSecondary; here the kept one is drawn, so that a photon path and an eye path keep theirs
// independently and the product of their weights stays unbiased), and from then on refracts by
// that wavelength's index:
//   - glass: a reflection goes the same way for every wavelength, so it keeps all three, each
//     weighted by its own Fresnel reflectance over the probability of reflecting (their mean);
//     a refraction keeps wavelength j with probability proportional to 1 - F_j;
//   - pbr transmission (diffuse and glossy lobes besides): the path keeps one wavelength where it
//     meets the material (meetDispersion), before its direct light, its hit point or its sample.
#ifndef PHOTON_SHARED_DISPERSION_H
#define PHOTON_SHARED_DISPERSION_H

#include "bsdf.h"
#include "spectral.h"

PH_NAMESPACE_BEGIN

PH_FN bool disperses(BUF_PARAM PH_IN(Material) m) {
    return isSpectral(BUF(params).flags) && m.dispersion > 0.0f;
}

PH_FN float cauchyTerm(BUF_PARAM uint channel) {
    vec4 c = BUF(params).spectrum.cauchy;
    return channel == 0u ? c.x : (channel == 1u ? c.y : c.z);
}

PH_FN float dispersedIor(BUF_PARAM PH_IN(Material) m, uint channel) {
    return max(m.ior + (m.ior - 1.0f) * m.dispersion * cauchyTerm(BUF_ARG channel), 1.0f);
}

PH_FN vec3 onlyChannel(vec3 weight, uint channel, float scale) {
    return vec3(channel == 0u ? scale * weight.x : 0.0f, channel == 1u ? scale * weight.y : 0.0f,
                channel == 2u ? scale * weight.z : 0.0f);
}

// A path (its weight and CHANNEL_*) meets material m: m refracts by the index of the wavelength the
// path kept, and a pbr material makes a path that carries all three keep one (one draw).
PH_FN void meetDispersion(BUF_PARAM PH_INOUT(Material) m, PH_INOUT(uint) channel, PH_INOUT(vec3) weight,
                          PH_INOUT(Rng) rng) {
    if (!disperses(BUF_ARG m)) {
        return;
    }
    if (channel == CHANNEL_ALL && m.type != MATERIAL_GLASS) {
        float u = rngNext(rng);
        channel = min(uint(u * 3.0f), 2u);
        weight = onlyChannel(weight, channel, 3.0f);
    }
    if (channel != CHANNEL_ALL) {
        m.ior = dispersedIor(BUF_ARG m, channel);
    }
}

// Dispersive glass met by a path that carries all three wavelengths (n: the geometric normal,
// ns the shading normal, as sampleBsdf takes them): reflect with the mean of the three Fresnel
// reflectances, or refract by one wavelength's index, which the path then keeps. Two draws.
PH_FN BsdfSample sampleDispersiveGlass(BUF_PARAM PH_IN(Material) m, vec3 wo, vec3 n, vec3 ns, PH_INOUT(uint) channel,
                                       PH_INOUT(Rng) rng) {
    float u0 = rngNext(rng);
    float u1 = rngNext(rng);
    float side = dot(wo, n) >= 0.0f ? 1.0f : -1.0f;
    vec3 nf = ns * side;
    bool entering = side > 0.0f;
    vec3 reflectance;
    for (uint i = 0u; i < 3u; ++i) {
        float ior = dispersedIor(BUF_ARG m, i);
        reflectance[i] = fresnelDielectric(dot(wo, nf), entering ? ior : 1.0f / ior);
    }
    float pReflect = (reflectance.x + reflectance.y + reflectance.z) / 3.0f;
    BsdfSample bs;
    bs.lobe = LOBE_SPECULAR;
    bool transmits = false;
    if (u0 < pReflect) {
        bs.direction = reflectAbout(wo, nf);
        bs.weight = reflectance / pReflect;
    } else {
        // Wavelength j with probability (1 - F_j) / Σ(1 - F_k): its weight (1 - F_j) / ((1 - pReflect)
        // · that probability) is 3 for every j. A wavelength reflected totally (F = 1) is never kept.
        vec3 transmittance = vec3(1.0f) - reflectance;
        float total = transmittance.x + transmittance.y + transmittance.z;
        float pick = u1 * total;
        uint j = pick < transmittance.x ? 0u : (pick < transmittance.x + transmittance.y ? 1u : 2u);
        if (transmittance[j] <= 0.0f) {
            j = transmittance.y > 0.0f ? 1u : (transmittance.x > 0.0f ? 0u : 2u);
        }
        float ior = dispersedIor(BUF_ARG m, j);
        vec3 wt = nf;
        if (!refractThrough(wo, nf, entering ? ior : 1.0f / ior, wt)) {
            bs.lobe = LOBE_NONE;  // (not reached: a kept wavelength refracts)
            bs.direction = nf;
            bs.weight = vec3(0.0f);
            return bs;
        }
        channel = j;
        bs.direction = unitVector(wt);
        bs.weight = onlyChannel(m.specular, j, 3.0f);
        transmits = true;
    }
    return absorbAcrossSurface(bs, n, side, transmits);
}

// sampleBsdf for a path with CHANNEL_* `channel`, after meetDispersion: dispersive glass by
// sampleDispersiveGlass while the path carries all three wavelengths.
PH_FN BsdfSample sampleBsdfAlongPath(BUF_PARAM PH_IN(Material) m, vec3 wo, vec3 n, vec3 ns, PH_INOUT(uint) channel,
                                     PH_INOUT(Rng) rng) {
    if (channel == CHANNEL_ALL && m.type == MATERIAL_GLASS && disperses(BUF_ARG m)) {
        return sampleDispersiveGlass(BUF_ARG m, wo, n, ns, channel, rng);
    }
    return sampleBsdf(m, wo, n, ns, rng);
}

PH_NAMESPACE_END

#endif
