// Every buffer the stages read or write, declared once. PH_BUFFERS is a list that the C and GLSL
// preprocessors both expand: into GLSL buffer declarations, into the C++/CUDA Bindings struct that
// the backends fill with their own pointers (host memory, device memory), into the table the hosts
// size, upload and check buffers from (kBuffers), and into the layout test's strides. Adding a
// buffer is one row here plus its struct in layout.h.
//
// A row is X(NAME, binding, element type, name, access, size):
//   NAME     the binding constant is BINDING_<NAME>
//   binding  its number; rows are numbered 1, 2, 3, ... (binding 0 is the FrameParams uniform)
//   access   RO: read-only everywhere; RW: written by some stage; MAPS and HITS: written by some
//            stage, read-only in shaders that define PH_PHOTON_MAPS_READONLY or PH_HIT_POINTS_READONLY
//            (drivers can then serve those loads from read-only caches)
//   size     how many elements the host allocates (BUFFER_PER_*, sized in core/frame/buffers.cpp)
#ifndef PHOTON_SHARED_BINDINGS_H
#define PHOTON_SHARED_BINDINGS_H

#include "layout.h"

#define PH_BUFFERS(X)                                                          \
    X(SPHERES, 1u, Sphere, spheres, RO, SCENE)                                 \
    X(PLANES, 2u, Plane, planes, RO, SCENE)                                    \
    X(QUADS, 3u, Quad, quads, RO, SCENE)                                       \
    X(TRIANGLES, 4u, Triangle, triangles, RO, SCENE)                           \
    X(TRIANGLE_ATTRIBUTES, 5u, TriangleAttributes, triangleAttributes, RO, SCENE) \
    X(MATERIALS, 6u, Material, materials, RO, SCENE)                           \
    X(TEXTURES, 7u, Texture, textures, RO, SCENE)                              \
    X(TEXELS, 8u, uvec2, texels, RO, SCENE)                                    \
    X(LIGHTS, 9u, Light, lights, RO, SCENE)                                    \
    X(EMISSIVE_TRIANGLES, 10u, EmissiveTriangle, emissiveTriangles, RO, SCENE) \
    X(TARGETS, 11u, CausticTarget, targets, RO, SCENE)                         \
    X(BVH_NODES, 12u, WideBvhNode, bvhNodes, RO, SCENE)                        \
    X(PRIMITIVE_REFS, 13u, uint, primitiveRefs, RO, SCENE)                     \
    X(PHOTONS, 14u, Photon, photons, RW, PHOTON)                               \
    X(PHOTON_KEYS, 15u, uint, photonKeys, RW, PHOTON)                          \
    X(SORTED_PHOTONS, 16u, MapPhoton, sortedPhotons, MAPS, PHOTON)             \
    X(CELL_COUNTS, 17u, uint, cellCounts, RW, CELL)                            \
    X(CELL_START, 18u, uint, cellStart, MAPS, CELL)                            \
    X(COUNTERS, 19u, uint, counters, RW, COUNTER)                              \
    X(HIT_POINTS, 20u, HitPoint, hitPoints, HITS, PIXEL)                       \
    X(FRAME, 21u, vec4, frameRadiance, RW, PIXEL)                              \
    X(ACCUMULATION, 22u, vec4, accumulation, RW, PIXEL)                        \
    X(SPPM_PIXELS, 23u, SppmPixel, sppmPixels, RW, SPPM_PIXEL)              \
    X(INFINITE_LIGHTS, 24u, Light, infiniteLights, RO, SCENE)                  \
    X(ENVIRONMENT_TEXELS, 25u, uint, environmentTexels, RO, SCENE)             \
    X(ENVIRONMENT_CDF, 26u, float, environmentCdf, RO, SCENE)                  \
    X(PHOTON_ORDER, 27u, uint, photonOrder, RW, ORDERED_PHOTON)              \
    X(AOVS, 28u, PixelAov, aovs, RW, AOV_PIXEL)                              \
    X(DENOISE, 29u, uvec4, denoisePlanes, RW, DENOISE_PLANE)                 \
    X(DENOISED, 30u, vec4, denoised, RW, DENOISE_PIXEL)                    \
    X(HISTORY, 31u, HistoryPixel, history, RW, HISTORY_PIXEL)               \
    X(MEDIA, 32u, Medium, media, RO, SCENE)                                 \
    X(DENSITIES, 33u, float, densities, RO, SCENE)

PH_NAMESPACE_BEGIN

// How many elements a buffer holds (the list's last column, BufferInfo::size).
PH_CONST uint BUFFER_PER_SCENE = 0u;    // the scene's array (one zeroed element when it is empty)
PH_CONST uint BUFFER_PER_PHOTON = 1u;   // PhotonBudget::totalCapacity(): both maps side by side
PH_CONST uint BUFFER_PER_CELL = 2u;     // PhotonBudget::totalCellEntries(): both grids' cells
PH_CONST uint BUFFER_PER_PIXEL = 3u;    // width × height
PH_CONST uint BUFFER_PER_COUNTER = 4u;  // COUNTER_COUNT
PH_CONST uint BUFFER_PER_SPPM_PIXEL = 5u;  // width × height with the sppm estimator, else one element
PH_CONST uint BUFFER_PER_ORDERED_PHOTON = 6u;  // ORDER_ARRAYS per photon for deterministic maps, else one
PH_CONST uint BUFFER_PER_AOV_PIXEL = 7u;      // width × height when the auxiliary images are kept, else one
PH_CONST uint BUFFER_PER_DENOISE_PIXEL = 8u;  // width × height when the denoiser runs, else one
PH_CONST uint BUFFER_PER_HISTORY_PIXEL = 9u;  // width × height when the history follows the camera (reproject.h), else one
PH_CONST uint BUFFER_PER_DENOISE_PLANE = 10u;  // DENOISE_PLANES × width × height when the denoiser runs, else one
PH_CONST uint BUFFER_SIZE_CLASS_COUNT = 11u;

PH_CONST uint BINDING_PARAMS = 0u;  // FrameParams (uniform)
#define PH_BINDING_CONSTANT(NAME, b, T, name, access, sizeClass) PH_CONST uint BINDING_##NAME = b;
PH_BUFFERS(PH_BINDING_CONSTANT)
#define PH_COUNT_ROW(NAME, b, T, name, access, sizeClass) 1u +
PH_CONST uint BINDING_COUNT = 1u + PH_BUFFERS(PH_COUNT_ROW) 0u;

PH_NAMESPACE_END

#ifndef __cplusplus
#ifdef PH_PHOTON_MAPS_READONLY
#define PH_ACCESS_MAPS readonly
#else
#define PH_ACCESS_MAPS
#endif
#ifdef PH_HIT_POINTS_READONLY
#define PH_ACCESS_HITS readonly
#else
#define PH_ACCESS_HITS
#endif
#define PH_ACCESS_RO readonly
#define PH_ACCESS_RW
layout(std140, set = 0, binding = BINDING_PARAMS) uniform ParamsBlock { FrameParams params; };
#define PH_DECLARE_BUFFER(NAME, b, T, name, access, sizeClass) \
    layout(std430, set = 0, binding = b) PH_ACCESS_##access restrict buffer name##Buffer { T name[]; };
PH_BUFFERS(PH_DECLARE_BUFFER)
#else
#include <cstddef>
namespace photon {

#define PH_POINTER_RO(T) const T*
#define PH_POINTER_RW(T) T*
#define PH_POINTER_MAPS(T) T*
#define PH_POINTER_HITS(T) T*
#define PH_BINDING_MEMBER(NAME, b, T, name, access, sizeClass) PH_POINTER_##access(T) name;

struct Bindings {
    FrameParams params;
    PH_BUFFERS(PH_BINDING_MEMBER)
};

// One row of the list, for the hosts.
struct BufferInfo {
    uint binding;
    const char* name;         // as in GLSL and Bindings
    std::size_t elementBytes;
    uint size;                // BUFFER_PER_*
    bool readOnly;            // RO: never written by a stage
};

#define PH_IS_READ_ONLY_RO true
#define PH_IS_READ_ONLY_RW false
#define PH_IS_READ_ONLY_MAPS false
#define PH_IS_READ_ONLY_HITS false
#define PH_BUFFER_INFO(NAME, b, T, name, access, sizeClass) {b, #name, sizeof(T), BUFFER_PER_##sizeClass, PH_IS_READ_ONLY_##access},
// kBuffers[i] is binding i + 1.
inline constexpr BufferInfo kBuffers[] = {PH_BUFFERS(PH_BUFFER_INFO)};
inline constexpr std::size_t kBufferCount = sizeof(kBuffers) / sizeof(kBuffers[0]);
static_assert(kBufferCount + 1 == BINDING_COUNT, "one binding per row, and the parameters");

constexpr bool buffersNumberedInOrder() {
    for (std::size_t i = 0; i < kBufferCount; ++i) {
        if (kBuffers[i].binding != i + 1) {
            return false;
        }
    }
    return true;
}
static_assert(buffersNumberedInOrder(), "PH_BUFFERS rows must be bindings 1, 2, 3, ... in order");

constexpr bool sizeClassesKnown() {
    for (const BufferInfo& info : kBuffers) {
        if (info.size >= BUFFER_SIZE_CLASS_COUNT) {
            return false;
        }
    }
    return true;
}
static_assert(sizeClassesKnown(), "every PH_BUFFERS row's size is a BUFFER_PER_* class");

inline const BufferInfo& bufferInfo(uint binding) { return kBuffers[binding - 1]; }

// Points every member of `b` at pointers[binding] (pointers[0], the parameters, is not used).
#define PH_POINT_MEMBER(NAME, b, T, name, access, sizeClass) \
    bindings.name = static_cast<PH_POINTER_##access(T)>(pointers[b]);
inline void pointBindings(Bindings& bindings, void* const* pointers) { PH_BUFFERS(PH_POINT_MEMBER) }

}  // namespace photon
#endif

#endif
