// Binding numbers and the buffers behind BUF(name). In GLSL every buffer is a global declared
// here; in C++ and CUDA the same names are members of Bindings, which the backends fill with
// their own pointers (host memory, device memory) and pass to every function that reads buffers.
#ifndef PHOTON_SHARED_BINDINGS_H
#define PHOTON_SHARED_BINDINGS_H

#include "layout.h"

PH_NAMESPACE_BEGIN

PH_CONST uint BINDING_PARAMS = 0u;          // FrameParams (uniform)
PH_CONST uint BINDING_SPHERES = 1u;
PH_CONST uint BINDING_PLANES = 2u;
PH_CONST uint BINDING_QUADS = 3u;
PH_CONST uint BINDING_TRIANGLES = 4u;
PH_CONST uint BINDING_MATERIALS = 5u;
PH_CONST uint BINDING_LIGHTS = 6u;
PH_CONST uint BINDING_TARGETS = 7u;          // CausticTarget
PH_CONST uint BINDING_PHOTONS = 8u;          // photons in the order they were traced, both maps
PH_CONST uint BINDING_PHOTON_KEYS = 9u;      // grid cell of each traced photon
PH_CONST uint BINDING_SORTED_PHOTONS = 10u;  // photons ordered by cell: the photon maps
PH_CONST uint BINDING_CELL_COUNTS = 11u;     // photons per cell, then the scatter cursors
PH_CONST uint BINDING_CELL_START = 12u;      // exclusive prefix sum of the counts, one extra entry
PH_CONST uint BINDING_COUNTERS = 13u;        // COUNTER_* slots
PH_CONST uint BINDING_HIT_POINTS = 14u;
PH_CONST uint BINDING_FRAME = 15u;           // this frame's radiance per pixel (vec4)
PH_CONST uint BINDING_ACCUMULATION = 16u;    // running mean over frames (vec4)
PH_CONST uint BINDING_COUNT = 17u;

PH_NAMESPACE_END

#ifndef __cplusplus
// A shader that only reads the photon maps or the hit points says so by defining
// PH_PHOTON_MAPS_READONLY or PH_HIT_POINTS_READONLY before including this file: drivers can then
// serve those loads from their read-only caches.
#ifdef PH_PHOTON_MAPS_READONLY
#define PH_MAPS_ACCESS readonly
#else
#define PH_MAPS_ACCESS
#endif
#ifdef PH_HIT_POINTS_READONLY
#define PH_HITS_ACCESS readonly
#else
#define PH_HITS_ACCESS
#endif
layout(std140, set = 0, binding = BINDING_PARAMS) uniform ParamsBlock { FrameParams params; };
layout(std430, set = 0, binding = BINDING_SPHERES) readonly restrict buffer SphereBuffer { Sphere spheres[]; };
layout(std430, set = 0, binding = BINDING_PLANES) readonly restrict buffer PlaneBuffer { Plane planes[]; };
layout(std430, set = 0, binding = BINDING_QUADS) readonly restrict buffer QuadBuffer { Quad quads[]; };
layout(std430, set = 0, binding = BINDING_TRIANGLES) readonly restrict buffer TriangleBuffer { Triangle triangles[]; };
layout(std430, set = 0, binding = BINDING_MATERIALS) readonly restrict buffer MaterialBuffer { Material materials[]; };
layout(std430, set = 0, binding = BINDING_LIGHTS) readonly restrict buffer LightBuffer { Light lights[]; };
layout(std430, set = 0, binding = BINDING_TARGETS) readonly restrict buffer TargetBuffer { CausticTarget targets[]; };
layout(std430, set = 0, binding = BINDING_PHOTONS) restrict buffer PhotonBuffer { Photon photons[]; };
layout(std430, set = 0, binding = BINDING_PHOTON_KEYS) restrict buffer PhotonKeyBuffer { uint photonKeys[]; };
layout(std430, set = 0, binding = BINDING_SORTED_PHOTONS) PH_MAPS_ACCESS restrict buffer SortedPhotonBuffer { Photon sortedPhotons[]; };
layout(std430, set = 0, binding = BINDING_CELL_COUNTS) restrict buffer CellCountBuffer { uint cellCounts[]; };
layout(std430, set = 0, binding = BINDING_CELL_START) PH_MAPS_ACCESS restrict buffer CellStartBuffer { uint cellStart[]; };
layout(std430, set = 0, binding = BINDING_COUNTERS) restrict buffer CounterBuffer { uint counters[]; };
layout(std430, set = 0, binding = BINDING_HIT_POINTS) PH_HITS_ACCESS restrict buffer HitPointBuffer { HitPoint hitPoints[]; };
layout(std430, set = 0, binding = BINDING_FRAME) restrict buffer FrameBuffer { vec4 frameRadiance[]; };
layout(std430, set = 0, binding = BINDING_ACCUMULATION) restrict buffer AccumulationBuffer { vec4 accumulation[]; };
#else
namespace photon {
struct Bindings {
    FrameParams params;
    const Sphere* spheres;
    const Plane* planes;
    const Quad* quads;
    const Triangle* triangles;
    const Material* materials;
    const Light* lights;
    const CausticTarget* targets;
    Photon* photons;
    uint* photonKeys;
    Photon* sortedPhotons;
    CompactPhoton* compactPhotons;  // the compact-photon experiment only (CUDA); no GLSL binding
    uint* cellCounts;
    uint* cellStart;
    uint* counters;
    HitPoint* hitPoints;
    glm::vec4* frameRadiance;
    glm::vec4* accumulation;
};
}  // namespace photon
#endif

#endif
