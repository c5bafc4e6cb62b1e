// What each light type is, answered in one place (in the manner of pbrt-v4's LightType), and where
// each type keeps its parameters in a Light. A Light is one std430 struct for every type, so some
// of its fields hold different things for different types; every stage reads them through the
// accessors below, whose names say what the field is for that type. The host writes them in
// Scene's add*Light functions and Scene::finalize, which refuses a type it does not know: no
// kernel ever sees one, and the switches over types here and in lights.h have a case for each.
#ifndef PHOTON_SHARED_LIGHT_TYPES_H
#define PHOTON_SHARED_LIGHT_TYPES_H

#include "layout.h"

PH_NAMESPACE_BEGIN

PH_CONST uint LIGHT_FLAG_DELTA_POSITION = 1u;   // emits from one point: no ray can hit it
PH_CONST uint LIGHT_FLAG_DELTA_DIRECTION = 2u;  // emits along one direction: no ray can hit it
PH_CONST uint LIGHT_FLAG_AREA = 4u;             // a surface of the scene emits: rays hit it
PH_CONST uint LIGHT_FLAG_INFINITE = 8u;         // surrounds the scene: rays that leave it see it

PH_FN uint lightFlags(uint type) {
    PH_COVERS(LIGHT_TYPE_COUNT, 7u);
    switch (type) {
        case LIGHT_POINT:
        case LIGHT_SPOT:
            return LIGHT_FLAG_DELTA_POSITION;
        case LIGHT_SPHERE:
        case LIGHT_QUAD:
        case LIGHT_TRIANGLES:
            return LIGHT_FLAG_AREA;
        case LIGHT_DIRECTIONAL:
            return LIGHT_FLAG_DELTA_DIRECTION;
        case LIGHT_ENVIRONMENT:
            return LIGHT_FLAG_INFINITE;
    }
    return 0u;  // no such type (Scene::finalize refuses it)
}

PH_FN bool isAreaLight(PH_IN(Light) light) { return (lightFlags(light.type) & LIGHT_FLAG_AREA) != 0u; }

// ---- Where each type keeps what (the fields of Light) -----------------------------------------
// Every type: type, power (the flux Φ it emits [W per channel], 0 for what emits no photons),
// pickCdf and pickProbability (how photon emission picks it among the scene's lights).

// LIGHT_POINT: profile (EMIT_*); a hemispherical one emits about its axis.
PH_FN vec3 pointPosition(PH_IN(Light) light) { return light.position; }
PH_FN vec3 hemisphereAxis(PH_IN(Light) light) { return light.axis; }

// LIGHT_SPOT: also spotOuter, spotInner (1 - cos of the cone's and the falloff's half-angles) and
// falloffMean (the falloff's mean over the cone). pointPosition is its position too.
PH_FN vec3 spotAxis(PH_IN(Light) light) { return light.axis; }

// LIGHT_SPHERE and LIGHT_QUAD: area, the emitting area.
PH_FN vec3 sphereCenter(PH_IN(Light) light) { return light.position; }
PH_FN float sphereRadius(PH_IN(Light) light) { return light.extent; }
PH_FN vec3 quadCorner(PH_IN(Light) light) { return light.position; }
PH_FN vec3 quadEdgeU(PH_IN(Light) light) { return light.vectorU; }
PH_FN vec3 quadEdgeV(PH_IN(Light) light) { return light.vectorV; }
PH_FN vec3 quadNormal(PH_IN(Light) light) { return light.axis; }  // unit, the emitting side

// LIGHT_TRIANGLES: emitterFirst and emitterCount, its slice of emissiveTriangles.

// LIGHT_DIRECTIONAL: parallel light over the sphere bounding the scene (Scene::finalize sizes it;
// power is the flux E·πR² through the sphere's disk). boundingCenter and boundingRadius serve
// LIGHT_ENVIRONMENT too.
PH_FN vec3 directionalDirection(PH_IN(Light) light) { return light.axis; }  // of travel, unit
PH_FN vec3 directionalIrradiance(PH_IN(Light) light) { return light.vectorU; }  // E on a surface facing it
PH_FN vec3 boundingCenter(PH_IN(Light) light) { return light.position; }
PH_FN float boundingRadius(PH_IN(Light) light) { return light.extent; }

// LIGHT_ENVIRONMENT (shared/environment.h): radiance from every direction, uniform or from an
// equirectangular map of environmentWidth × environmentHeight texels (height 0: uniform), times
// environmentScale; the map's axes in the world (its rotation's columns); boundingCenter and
// boundingRadius, as for a directional light, bound the scene; its photons start on the faces of
// the scene's bounding box that face their direction (boundsHalfExtent).
PH_FN vec3 environmentScale(PH_IN(Light) light) { return light.vectorU; }  // the uniform radiance, or the map's factor
PH_FN uint environmentWidth(PH_IN(Light) light) { return light.emitterFirst; }
PH_FN uint environmentHeight(PH_IN(Light) light) { return light.emitterCount; }
PH_FN vec3 environmentMapX(PH_IN(Light) light) { return light.vectorV; }
PH_FN vec3 environmentMapY(PH_IN(Light) light) { return light.axis; }  // the map's zenith in the world
PH_FN vec3 environmentMapZ(PH_IN(Light) light) { return cross(light.vectorV, light.axis); }
// The scene's bounding box about boundingCenter, where the environment's photons start.
PH_FN vec3 boundsHalfExtent(PH_IN(Light) light) { return vec3(light.area, light.spanY, light.spanZ); }

PH_NAMESPACE_END

#endif
