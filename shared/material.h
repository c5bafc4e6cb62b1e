// What each material does, answered in one place (in the manner of pbrt-v4's BxDFFlags). Every
// stage and the host ask materialFlags() instead of comparing material types:
//   photons are stored where reflection is not a delta distribution, and density estimates read them;
//   eye paths end there too (a mirror coat may continue them instead);
//   mirrors and glass are caustic casters: bounded ones are the targets of the caustic pass;
//   a mirror coat over a stored base (reflective) makes caustic paths but is not a target;
//   emitters radiate and absorb; any other material may radiate too (an emissive glTF surface).
#ifndef PHOTON_SHARED_MATERIAL_H
#define PHOTON_SHARED_MATERIAL_H

#include "layout.h"
#include "math.h"

PH_NAMESPACE_BEGIN

PH_CONST uint SURFACE_STORES_PHOTONS = 1u;   // a non-delta lobe: photons are stored, estimates read them
PH_CONST uint SURFACE_ENDS_EYE_PATHS = 2u;   // eye paths end here with direct light and photon estimates
PH_CONST uint SURFACE_CAUSTIC_CASTER = 4u;   // traced lobes only (mirror, glass; smooth metal, pbr glass)
PH_CONST uint SURFACE_SPECULAR_COAT = 8u;    // a traced lobe over a stored base (reflective; pbr)
PH_CONST uint SURFACE_EMITS = 16u;           // the visible surface of an area light
PH_CONST uint SURFACE_LAMBERTIAN = 32u;      // what is stored reflects as albedo/π: estimates take it
                                             // out of their sums

// The glTF metallic-roughness material (MATERIAL_PBR, pbr.h) splits its lobes by roughness into
// the ones eye and photon paths follow by sampling (as they follow mirrors and glass) and the ones
// density estimates read (as for Lambertian and glossy surfaces):
//   traced: the specular lobes (dielectric and metal) of GGX α below PBR_TRACED_ALPHA, and the
//           transmission of any roughness (what refracts cannot be estimated from the side it
//           left); photons that take them stay on caustic paths;
//   stored: the diffuse lobe, and the specular lobes from PBR_TRACED_ALPHA up.
// Below PBR_DELTA_ALPHA a specular lobe is a delta distribution to direct light too: shadow rays
// cannot find its highlight, so emitters are counted where its sampled ray meets them.
PH_CONST float PBR_TRACED_ALPHA = 0.09f;  // perceptual roughness 0.3
PH_CONST float PBR_DELTA_ALPHA = 0.0025f;  // perceptual roughness 0.05

PH_FN bool pbrHasStoredLobes(PH_IN(Material) m) {
    return (m.metallic < 1.0f && m.transmission < 1.0f) || (m.metallic > 0.0f && m.roughness >= PBR_TRACED_ALPHA);
}

PH_FN bool pbrHasTracedLobes(PH_IN(Material) m) {
    return (m.roughness < PBR_TRACED_ALPHA && (m.metallic > 0.0f || m.transmission < 1.0f)) ||
           (m.metallic < 1.0f && m.transmission > 0.0f);
}

// What a glTF material does (its emission aside), by which of its lobes are traced and which stored.
PH_FN uint pbrFlags(PH_IN(Material) m) {
    if ((m.flags & MATERIAL_FLAG_STORED_PART) != 0u || !pbrHasTracedLobes(m)) {
        return SURFACE_STORES_PHOTONS | SURFACE_ENDS_EYE_PATHS;
    }
    if (!pbrHasStoredLobes(m)) {
        return SURFACE_CAUSTIC_CASTER;
    }
    return SURFACE_STORES_PHOTONS | SURFACE_ENDS_EYE_PATHS | SURFACE_SPECULAR_COAT;
}

PH_FN uint materialFlags(PH_IN(Material) m) {
    uint emits = isBlack(m.emission) ? 0u : SURFACE_EMITS;  // any material may also emit (glTF, MTL Ke)
    PH_COVERS(MATERIAL_TYPE_COUNT, 7u);
    switch (m.type) {
        case MATERIAL_DIFFUSE:
            return emits | SURFACE_STORES_PHOTONS | SURFACE_ENDS_EYE_PATHS | SURFACE_LAMBERTIAN;
        case MATERIAL_GLOSSY:
            return emits | SURFACE_STORES_PHOTONS | SURFACE_ENDS_EYE_PATHS;
        case MATERIAL_REFLECTIVE:
            return emits | SURFACE_STORES_PHOTONS | SURFACE_ENDS_EYE_PATHS | SURFACE_SPECULAR_COAT | SURFACE_LAMBERTIAN;
        case MATERIAL_MIRROR:
        case MATERIAL_GLASS:
            return emits | SURFACE_CAUSTIC_CASTER;
        case MATERIAL_EMITTER:
            return SURFACE_EMITS;
        case MATERIAL_PBR:
            return emits | pbrFlags(m);
    }
    return 0u;  // no such type: Scene::finalize refuses it, so no kernel sees one
}

PH_FN bool surfaceIs(PH_IN(Material) m, uint flag) { return (materialFlags(m) & flag) != 0u; }

// Whether a photon path that meets this surface can become a caustic one (light, specular, diffuse).
PH_FN bool makesCausticPaths(PH_IN(Material) m) {
    return surfaceIs(m, SURFACE_CAUSTIC_CASTER | SURFACE_SPECULAR_COAT);
}

// Probability that a ray takes the specular lobe of a two-lobe material (reflective: its mirror
// coat; glossy: its GGX lobe), not its Lambertian base: the lobes' shares of the larger colours.
PH_FN float specularLobeProbability(PH_IN(Material) m) {
    float d = maxComponent(m.albedo);
    float s = maxComponent(m.specular);
    return (d + s) > 0.0f ? s / (d + s) : 0.0f;
}

// The part of a material that density estimates and shadow rays see: without its mirror coat,
// a delta lobe that only traced rays can follow.
PH_FN Material storedPart(PH_IN(Material) m) {
    Material d = m;
    if (m.type == MATERIAL_PBR) {
        d.flags |= MATERIAL_FLAG_STORED_PART;
    } else if (surfaceIs(m, SURFACE_SPECULAR_COAT)) {
        d.type = MATERIAL_DIFFUSE;
        d.specular = vec3(0.0f);
    }
    return d;
}

PH_NAMESPACE_END

#endif
