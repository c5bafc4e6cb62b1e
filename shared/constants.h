// Constants and enumerations shared by every backend. Enumerations are plain uint constants so that
// they mean the same in buffers, in GLSL and in C++; each has a *_COUNT, and the host's enums
// (core/settings/settings.h) are defined from these values and checked against the counts.
#ifndef PHOTON_SHARED_CONSTANTS_H
#define PHOTON_SHARED_CONSTANTS_H

#include "portable.h"

PH_NAMESPACE_BEGIN

PH_CONST float PI = 3.14159265358979323846f;
PH_CONST float TWO_PI = 6.28318530717958647692f;
PH_CONST float INV_PI = 0.31830988618379067154f;
PH_CONST float INV_TWO_PI = 0.15915494309189533577f;
PH_CONST float INV_FOUR_PI = 0.07957747154594766788f;
PH_CONST float FLOAT_MAX = 3.402823466e+38f;
PH_CONST uint NONE = 0xffffffffu;

// Material types (Material::type). What each one does is answered in one place: materialFlags().
PH_CONST uint MATERIAL_DIFFUSE = 0u;     // Lambertian: albedo/π
PH_CONST uint MATERIAL_MIRROR = 1u;      // perfect specular reflection, coloured by `specular`
PH_CONST uint MATERIAL_GLASS = 2u;       // smooth dielectric with exact Fresnel; transmission tinted by `specular`
PH_CONST uint MATERIAL_GLOSSY = 3u;      // Lambertian base + GGX microfacet lobe (Walter et al. 2007)
PH_CONST uint MATERIAL_EMITTER = 4u;     // the visible surface of an area light: emits, absorbs everything
PH_CONST uint MATERIAL_REFLECTIVE = 5u;  // Lambertian base under a perfect mirror coat (Whitted)
PH_CONST uint MATERIAL_PBR = 6u;         // glTF 2.0 metallic-roughness (its Appendix B), with transmission
PH_CONST uint MATERIAL_TYPE_COUNT = 7u;

// Material::flags bits.
PH_CONST uint MATERIAL_FLAG_ALPHA_MASK = 1u;   // cut out where coverage α < alphaCutoff (glTF MASK)
PH_CONST uint MATERIAL_FLAG_ALPHA_BLEND = 2u;  // present with probability α (glTF BLEND, stochastically)
PH_CONST uint MATERIAL_FLAG_THIN_WALLED = 4u;  // pbr transmission passes straight through (no volume)
PH_CONST uint MATERIAL_FLAG_STORED_PART = 8u;  // pbr: only the lobes density estimates see (storedPart)
PH_CONST uint MATERIAL_FLAG_SINGLE_SIDED = 16u;  // seen from its front only (glTF doubleSided false)

// Triangle::flags bits.
PH_CONST uint TRIANGLE_ALPHA_TESTED = 1u;      // its material's coverage decides whether a ray hits
PH_CONST uint TRIANGLE_BACK_CULLED = 2u;       // rays pass through its back (a single-sided opaque material)

// Light types (Light::type). What each one is, and where its parameters live in a Light, is
// answered in one place: lightFlags() and the accessors of light_types.h.
PH_CONST uint LIGHT_POINT = 0u;        // a point, isotropic or hemispherical (Light::profile)
PH_CONST uint LIGHT_SPOT = 1u;         // a point emitting into a cone, with a smooth falloff
PH_CONST uint LIGHT_SPHERE = 2u;       // a Lambertian sphere
PH_CONST uint LIGHT_QUAD = 3u;         // a one-sided Lambertian parallelogram
PH_CONST uint LIGHT_TRIANGLES = 4u;    // the emissive triangles of the scene, sampled by power
PH_CONST uint LIGHT_DIRECTIONAL = 5u;  // parallel light from infinity (the sun), over the scene's bounds
PH_CONST uint LIGHT_ENVIRONMENT = 6u;  // radiance from every direction that leaves the scene: uniform or a map
PH_CONST uint LIGHT_TYPE_COUNT = 7u;

// Emission profile of a point light (Light::profile).
PH_CONST uint EMIT_ISOTROPIC = 0u;   // I = Φ/4π in every direction
PH_CONST uint EMIT_HEMISPHERE = 1u;  // Lambertian point source about `axis`: I = Φ cosθ/π (Wu's light)

// Primitive kinds (Hit::kind).
PH_CONST uint PRIM_SPHERE = 0u;
PH_CONST uint PRIM_PLANE = 1u;
PH_CONST uint PRIM_QUAD = 2u;
PH_CONST uint PRIM_TRIANGLE = 3u;
PH_CONST uint PRIM_KIND_COUNT = 4u;

// Radiance estimators (FrameParams::estimator).
// Scenes of at most this many bounded primitives are intersected one by one, without the BVH: its
// node fetches and stack cost more than they save (the Cornell box's 7 primitives: measured).
PH_CONST uint LINEAR_PRIMITIVES_MAX = 8u;

PH_CONST uint ESTIMATOR_CELL = 0u;         // Wu's estimate: the photons of the containing grid cell
PH_CONST uint ESTIMATOR_RADIUS = 1u;       // fixed radius, filtered by a kernel
PH_CONST uint ESTIMATOR_KNN = 2u;          // k nearest photons within a maximum radius (Jensen)
PH_CONST uint ESTIMATOR_PROGRESSIVE = 3u;  // fixed radius per frame, shrinking (Knaus & Zwicker 2011)
PH_CONST uint ESTIMATOR_SPPM = 4u;         // per-pixel radius and flux, stochastic progressive (Hachisuka & Jensen 2009)
PH_CONST uint ESTIMATOR_COUNT = 5u;

// Density-estimation kernels (FrameParams::kernel).
PH_CONST uint KERNEL_BOX = 0u;
PH_CONST uint KERNEL_CONE = 1u;          // Jensen's cone filter, k = 1
PH_CONST uint KERNEL_EPANECHNIKOV = 2u;
PH_CONST uint KERNEL_COUNT = 3u;

// Photon map grids (GridParams::kind).
PH_CONST uint GRID_BOUNDED = 0u;  // k³ cells over the scene's bounding cube, clamped (Wu's grid)
PH_CONST uint GRID_HASHED = 1u;   // unbounded cells hashed into a table (Teschner et al. 2003)
PH_CONST uint GRID_KIND_COUNT = 2u;

// How the global map reaches the image (FrameParams::globalMode).
PH_CONST uint GLOBAL_DIRECT = 0u;        // estimate indirect light at the eye hit itself
PH_CONST uint GLOBAL_FINAL_GATHER = 1u;  // one bounce of gather rays, global map at their hits
PH_CONST uint GLOBAL_MODE_COUNT = 2u;

// What the gather stage writes (FrameParams::view).
PH_CONST uint VIEW_FINAL = 0u;
PH_CONST uint VIEW_DIRECT = 1u;   // emission + direct light only
PH_CONST uint VIEW_GLOBAL = 2u;   // global-map estimate only
PH_CONST uint VIEW_CAUSTIC = 3u;  // caustic-map estimate only
PH_CONST uint VIEW_GRID = 4u;     // photons in the hit point's cell, as a heat map
PH_CONST uint VIEW_VOLUME = 5u;   // the light media scatter towards the eye only (volume map)
PH_CONST uint VIEW_COUNT = 6u;

// Tone curves (display only, shared/tonemap.h).
PH_CONST uint TONEMAP_CLAMP = 0u;
PH_CONST uint TONEMAP_REINHARD = 1u;
PH_CONST uint TONEMAP_ACES = 2u;  // Narkowicz's fit of the ACES filmic curve
PH_CONST uint TONEMAP_COUNT = 3u;

// Whether the image is denoised (denoise.h).
PH_CONST uint DENOISE_OFF = 0u;
PH_CONST uint DENOISE_ON = 1u;
PH_CONST uint DENOISE_MODE_COUNT = 2u;

// Photon maps, one row each: the constant, its index, the name reports give it, the option of
// its query radius, and the host's first radius for the single-frame estimators (in median pixel
// footprints), the share of the global map's fallback radius, and sppm's first disc (photons it
// should hold, clamped to footprints min..max). Every per-map quantity (grids, capacities,
// counters, radii, sppm state) is an array indexed by MAP_*, and every host table is made from
// these rows, so that a further map is one row here plus the photon pass that fills it.
#define PH_MAPS(X)                                                                   \
    X(GLOBAL, 0u, "global", "--radius", 8.0f, 1.0f, 64u, 1.5f, 16.0f)                 \
    X(CAUSTIC, 1u, "caustic", "--caustic-radius", 4.0f, 0.5f, 64u, 1.0f, 8.0f)          \
    X(VOLUME, 2u, "volume", "--volume-radius", 8.0f, 2.0f, 64u, 1.5f, 16.0f)

// (No variadic macros: GLSL's preprocessor has none.)
#define PH_MAP_CONSTANT(NAME, id, name, radiusFlag, autoFootprints, fallbackShare, sppmPhotons, sppmMin, sppmMax) \
    PH_CONST uint MAP_##NAME = id;
PH_MAPS(PH_MAP_CONSTANT)
#define PH_COUNT_MAP(NAME, id, name, radiusFlag, autoFootprints, fallbackShare, sppmPhotons, sppmMin, sppmMax) 1u +
PH_CONST uint MAP_COUNT = PH_MAPS(PH_COUNT_MAP) 0u;
// The maps estimated at the eye paths' hit points (global, caustic: the first rows); the volume
// map is estimated along the eye rays through media (volume_estimate.h) and has no sppm state.
PH_CONST uint SURFACE_MAP_COUNT = 2u;

// Slots of the counters buffer, each a run of MAP_COUNT (the histograms: of MAP_COUNT × bins).
PH_CONST uint COUNTER_STORED = 0u;                   // photons appended to each map this frame
PH_CONST uint COUNTER_SPPM_RADIUS = MAP_COUNT;       // sppm: the largest radius of a pixel with photons (float bits)
PH_CONST uint SPPM_RADIUS_BINS = 64u;                // sppm: pixels with photons by the binary exponent of their radius
PH_CONST uint COUNTER_SPPM_HISTOGRAM = 2u * MAP_COUNT;  // each map's bins, in map order
PH_CONST uint COUNTER_ENVIRONMENT_PATHS = COUNTER_SPPM_HISTOGRAM + MAP_COUNT * SPPM_RADIUS_BINS;  // global-pass photons the environment emitted
PH_CONST uint COUNTER_ENVIRONMENT_HITS = COUNTER_ENVIRONMENT_PATHS + 1u;  // ... whose first ray met the scene
PH_CONST uint COUNTER_PATHS_TAKEN = COUNTER_ENVIRONMENT_HITS + 1u;  // paths a GPU's photon pool has handed out
PH_CONST uint COUNTER_COUNT = COUNTER_PATHS_TAKEN + 1u;

// sppm: photon counts per pixel, a slot per map (a multiple of 4: SppmPixel stays 16-byte sized).
PH_CONST uint SPPM_COUNT_SLOTS = 4u;

// sppm: a frame's photons of a map count as one photon pass per this many emitted paths (at most
// SPPM_BATCHES_MAX passes), so that radii shrink with the photons traced, not with the frames.
PH_CONST uint SPPM_BATCH_PATHS = 16384u;
PH_CONST uint SPPM_BATCHES_MAX = 256u;
// A pixel's first radius (sppmFirstRadius) is at most SPPM_FIRST_MAX_GUESSES times the
// even-spread guess and at least SPPM_FIRST_MIN_FOOTPRINTS pixel footprints.
PH_CONST float SPPM_FIRST_MAX_GUESSES = 4.0f;
PH_CONST float SPPM_FIRST_MIN_FOOTPRINTS = 0.5f;

// photonBounce() result bits.
PH_CONST uint STORE_GLOBAL = 1u;
PH_CONST uint STORE_CAUSTIC = 2u;
PH_CONST uint STORE_VOLUME = 4u;

// PhotonPath::flags bits.
PH_CONST uint PATH_ALIVE = 1u;
PH_CONST uint PATH_SPECULAR_ONLY = 2u;  // every bounce so far was a mirror or glass interaction
PH_CONST uint PATH_CAUSTIC_PASS = 4u;   // emitted towards a specular object for the caustic map
PH_CONST uint PATH_FROM_TARGET = 8u;    // its first surface was a caustic target (see photon_trace.h)
PH_CONST uint PATH_FROM_ENVIRONMENT = 16u;  // emitted by the environment (counted: COUNTER_ENVIRONMENT_*)
PH_CONST uint PATH_CHANNEL_SHIFT = 5u;      // bits 5-6: the path's CHANNEL_* (spectral.h)

// Which of the frame's three wavelengths a path carries (spectral.h): one of them, 0, 1 or 2,
// after a dispersive surface, else all.
PH_CONST uint CHANNEL_ALL = 3u;

// FrameParams::flags bits.
PH_CONST uint FLAG_PIXEL_CENTER = 1u;    // one ray through each pixel centre: no jitter, no lens
PH_CONST uint FLAG_SPLIT_CAUSTICS = 2u;  // caustic paths come from the caustic pass only
PH_CONST uint FLAG_DETERMINISTIC = 4u;   // the photon maps in canonical order (photon_map.h)
PH_CONST uint FLAG_SPECTRAL = 8u;        // paths carry the frame's three wavelengths (spectral.h)
PH_CONST uint FLAG_AOVS = 16u;           // accumulate keeps the auxiliary images (aov.h)
PH_CONST uint FLAG_DENOISE = 32u;        // the denoise stage filters the image (denoise.h); implies FLAG_AOVS
PH_CONST uint FLAG_REPROJECT = 64u;      // the camera moved: the reproject stage carries the history (reproject.h); implies FLAG_AOVS

// Temporal reprojection (reproject.h). A pixel keeps the history of the pixel that saw its surface
// in the frame before if that one's mean depth is within this share of the surface's distance
// from the previous camera and its mean normal's direction within acos(REPROJECT_NORMAL_COS) of
// the surface's (45°: a pixel across a right-angled corner, whose frames saw both sides, still
// passes); a carried history counts at most REPROJECT_MAX_FRAMES frames: each move's interpolation
// smears the image a little, and a longer history keeps the smear longer (measured on an orbit of
// the Cornell box and the caustic scene, docs/denoising.md: 4, 8, 16 and 32 frames; 8 is the best
// trade of noise against blur away from the focus).
PH_CONST float REPROJECT_DEPTH_TOLERANCE = 0.05f;
PH_CONST float REPROJECT_NORMAL_COS = 0.7f;
PH_CONST uint REPROJECT_MAX_FRAMES = 8u;
// Below this sum of bilinear weights of the pixels that saw the same surface, a pixel starts again.
PH_CONST float REPROJECT_MIN_WEIGHT = 0.01f;
// Its passes: every pixel's history set aside, then each pixel's taken from where its point was.
PH_CONST uint REPROJECT_PASS_SAVE = 0u;
PH_CONST uint REPROJECT_PASS_RESTORE = 1u;
PH_CONST uint REPROJECT_PASS_COUNT = 2u;

// The denoiser (denoise.h): an edge-avoiding à-trous wavelet filter guided by variance (Dammertz
// et al. 2010; Schied et al. 2017, SVGF), DENOISE_LEVELS passes of a 3 × 3 binomial kernel with
// holes 2^level. Its edge-stopping functions: normals max(0, n_p·n_q)^(2^DENOISE_NORMAL_SQUARINGS),
// depth exp(-|z_p - z_q| / (DENOISE_SIGMA_DEPTH |∇z| |p - q|)), luminance
// exp(-|l_p - l_q| / (DENOISE_SIGMA_LUMINANCE σ_l)).
PH_CONST uint DENOISE_LEVELS = 5u;
PH_CONST uint DENOISE_NORMAL_SQUARINGS = 7u;  // the exponent 128, SVGF's
PH_CONST float DENOISE_SIGMA_DEPTH = 1.0f;
PH_CONST float DENOISE_SIGMA_LUMINANCE = 4.0f;
// ... and albedo exp(-|a_p - a_q|₁ / DENOISE_SIGMA_ALBEDO): demodulation holds only where the
// light is the albedo times the illumination, which a metal's reflection beside paint is not.
PH_CONST float DENOISE_SIGMA_ALBEDO = 0.1f;
// Below this many frames a pixel's variance is estimated over its 7 × 7 neighbours, not its own
// frames (SVGF's rule for a short history).
PH_CONST uint DENOISE_TEMPORAL_FRAMES = 4u;
// Demodulation divides by the albedo, at least this (a black surface is not divided by zero).
PH_CONST float DENOISE_MIN_ALBEDO = 0.01f;
// The denoiser's images, planes of one uvec4 a pixel in the `denoisePlanes` buffer (plane p of
// pixel i at p · pixels + i): two of the demodulated radiance and its variance (float bits), which
// the levels read from and write to in turn, and the packed guides (denoise.h).
PH_CONST uint DENOISE_PLANE_RADIANCE = 0u;  // and 1
PH_CONST uint DENOISE_PLANE_GUIDE = 2u;
PH_CONST uint DENOISE_PLANES = 3u;
// The guides keep albedos in [0, DENOISE_ALBEDO_RANGE] to 10 bits a channel (only the edge-stopping
// weight reads them; remodulation reads the pixel's own albedo whole).
PH_CONST float DENOISE_ALBEDO_RANGE = 2.0f;
// The denoise stage's passes: the guides and variance (prepare), the levels, then the image
// (the last level multiplies the albedo back).
PH_CONST uint DENOISE_PASS_PREPARE = 0u;
PH_CONST uint DENOISE_PASS_LEVEL = 1u;  // level i is pass DENOISE_PASS_LEVEL + i
PH_CONST uint DENOISE_PASS_COUNT = DENOISE_PASS_LEVEL + DENOISE_LEVELS;

// Independent random streams, so that no two stages draw the same numbers.
PH_CONST uint STREAM_PHOTON = 0x1b873593u;
PH_CONST uint STREAM_CAMERA = 0xcc9e2d51u;
PH_CONST uint STREAM_GATHER = 0x85ebca6bu;
PH_CONST uint STREAM_MAP_PHOTON = 0xe6546b64u;  // the rounding of powers into the maps (map_photon.h)

// A stored photon's identity: its path and the bounce at which it was stored, (path << 6) | bounce.
// Unique within a map, and the same on every backend, so it gives each cell a canonical order.
PH_CONST uint PHOTON_BOUNCE_BITS = 6u;      // bounces 0..63: max_photon_depth is at most 64
PH_CONST uint PHOTON_PATHS_MAX = 67108864u;  // 2^26 photon paths a frame, so that ids fit 32 bits

// TriangleAttributes::flags bits.
PH_CONST uint ATTRIBUTE_NORMALS = 1u;    // the vertex normals are set
PH_CONST uint ATTRIBUTE_TEXCOORDS = 2u;  // the texture coordinates are set
PH_CONST uint ATTRIBUTE_TANGENT = 4u;    // the tangent is set (with texture coordinates)
PH_CONST uint ATTRIBUTE_FLIPPED_BITANGENT = 8u;  // the bitangent is −(n × t): a mirrored texture mapping

// Texture wrap modes (the glTF sampler's), for s and t (Texture::wrap).
PH_CONST uint WRAP_REPEAT = 0u;
PH_CONST uint WRAP_CLAMP = 1u;           // clamp to the edge
PH_CONST uint WRAP_MIRRORED_REPEAT = 2u;

// Fixed capacities.
PH_CONST uint EYE_SPLITS_MAX = 4u;        // most interfaces an eye path splits at (eye_trace.h)
PH_CONST float BRANCH_NEIGHBOURS = 64.0f;  // photons in the first radius of a branch's estimate (eye_trace.h)
PH_CONST uint KNN_MAX = 64u;              // largest k of the k-nearest estimator
PH_CONST uint CAUSTIC_TARGETS_MAX = 64u;  // specular objects the caustic pass aims at
PH_CONST uint LIGHTS_MAX = 64u;
PH_CONST uint BVH_STACK_SIZE = 96u;       // the traversal's stack: the host refuses hierarchies that need more

// A wide BVH node's children (WideBvhNode): four, and what byte i of its `kinds` says of child i
// besides a leaf's primitive count (1 .. BVH_LEAF_MAX).
PH_CONST uint BVH_WIDTH = 4u;
PH_CONST uint BVH_LEAF_MAX = 4u;
PH_CONST uint WIDE_CHILD_EMPTY = 0u;      // no child: the node's children before it are all it has
PH_CONST uint WIDE_CHILD_INNER = 255u;
// The traversal's word for a leaf child (intersect.h): this bit, its count − 1 in the two bits
// below, its first primitive reference in the rest.
PH_CONST uint WIDE_LEAF_CODE = 0x80000000u;
PH_CONST uint WIDE_LEAF_COUNT_SHIFT = 29u;
PH_CONST uint WIDE_LEAF_FIRST_MASK = (1u << 29u) - 1u;
#ifdef __cplusplus
static_assert(BVH_LEAF_MAX <= 4u, "a leaf's count − 1 fits the traversal's two bits");
#endif

PH_NAMESPACE_END

#endif
