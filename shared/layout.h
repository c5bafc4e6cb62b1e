// Buffer layouts: the one definition of every struct that crosses from host to device.
// Written so that C++ (GLM, tightly packed vec3) and GLSL std430 (vec3 aligned to 16) agree:
// each vec3 is followed by a 4-byte scalar, each struct is a multiple of 16 bytes, and every
// offset is asserted below. Uniform blocks use std140, which equals std430 for these structs.
#ifndef PHOTON_SHARED_LAYOUT_H
#define PHOTON_SHARED_LAYOUT_H

#include "constants.h"
#ifdef __cplusplus
#include <cstddef>
#define PH_OFFSET(T, member, offset) static_assert(offsetof(T, member) == offset, #T "::" #member " offset")
#define PH_SIZE(T, size) static_assert(sizeof(T) == size, "sizeof(" #T ")")
#else
#define PH_OFFSET(T, member, offset)
#define PH_SIZE(T, size)
#endif

PH_NAMESPACE_BEGIN

// ---- Scene ------------------------------------------------------------------------------------

struct PH_ALIGN16 Sphere {
    vec3 center; float radius;
    uint material; uint pad0; uint pad1; uint pad2;
};

// The plane dot(normal, x) = offset.
struct PH_ALIGN16 Plane {
    vec3 normal; float offset;
    uint material; uint pad0; uint pad1; uint pad2;
};

// The parallelogram corner + a·edgeU + b·edgeV, a, b ∈ [0, 1].
struct PH_ALIGN16 Quad {
    vec3 corner; uint material;
    vec3 edgeU; float area;
    vec3 edgeV; float pad0;
    vec3 w; float pad1;  // cross(edgeU, edgeV) / |cross(edgeU, edgeV)|²: gives (a, b) of a point
};

// A triangle by its vertices, wound counter-clockwise about its front (geometric normal
// (v1 - v0) × (v2 - v0)).
struct PH_ALIGN16 Triangle {
    vec3 v0; uint material;
    vec3 v1; uint attributes;  // its TriangleAttributes, or NONE: flat, no texture coordinates
    vec3 v2; uint flags;       // TRIANGLE_* bits, from its material (Scene::finalize)
};

// What a mesh triangle carries besides its vertices: vertex normals for smooth shading and
// texture coordinates (s, t) at each vertex.
struct PH_ALIGN16 TriangleAttributes {
    uint normal0; uint normal1; uint normal2; uint flags;  // octahedral vertex normals; ATTRIBUTE_* bits
    float s0; float t0; float s1; float t1;
    float s2; float t2; uint tangent; float pad0;  // tangent: octahedral unit ∂p/∂s of the triangle
};

struct PH_ALIGN16 Material {
    vec3 albedo; uint type;          // diffuse reflectance ρ (diffuse, glossy, reflective); base colour (pbr)
    vec3 specular; float roughness;  // mirror reflectance, glass tint, glossy lobe colour; GGX α
    vec3 emission; float ior;        // emitted radiance (front side); index of refraction (glass, pbr)
    uint albedoTexture; uint metallicRoughnessTexture; uint normalTexture; uint emissionTexture;
    // Textures (each NONE or a Texture): albedoTexture multiplies albedo and alpha;
    // metallicRoughnessTexture metallic (blue) and perceptual roughness (green); normalTexture a
    // tangent-space normal; emissionTexture multiplies emission
    float metallic; float transmission; float alpha; float alphaCutoff;
    // pbr: metallic and transmission factors ∈ [0, 1]; every type: coverage α (MASK: cut out where
    // α < alphaCutoff; BLEND: kept with probability α)
    vec3 attenuation; uint flags;    // absorption coefficient σa [1/m] inside (Beer–Lambert); MATERIAL_FLAG_*
    float normalScale; float dispersion; uint medium; uint pad2;
    // normalScale: scale of the normal texture's x and y; dispersion: 20 / V_d of glass and pbr
    // transmission, V_d the Abbe number (glTF KHR_materials_dispersion; 0: none), spectral.h;
    // medium: the participating medium inside (a Medium; NONE: none), medium.h
};

// A participating medium (medium.h): what fills the inside of the objects whose material names
// it, or the scene (SceneInfo.medium) within its box. Homogeneous, or heterogeneous: its
// coefficients scaled by a density grid whose voxels tile the box (medium_grid.h).
struct PH_ALIGN16 Medium {
    vec3 absorption; float g;      // absorption coefficient σa [1/m]; Henyey–Greenstein's mean cosine
    vec3 scattering; uint grid;    // scattering coefficient σs [1/m]; grid: its first voxel in
                                   // densities (NONE: homogeneous, density 1)
    vec3 lower; float pad0;        // the box it fills (the scene's medium: its bounds; an object's:
    vec3 upper; float pad1;        // everything, the object bounds it; a grid's: the grid's)
    uvec3 resolution; uint pad2;   // the grid's voxels along x, y, z (x fastest in densities)
};

// An image in the texels buffer: width × height texels from `offset`, row by row from the top, as
// a material sees it: through a transform of its texture coordinates (KHR_texture_transform).
struct PH_ALIGN16 Texture {
    uint offset; uint width; uint height; uint wrap;  // wrap: WRAP_* of s | (WRAP_* of t) << 4
    vec3 transformS; uint pad0;      // s' = dot(transformS, (s, t, 1))
    vec3 transformT; uint pad1;      // t' = dot(transformT, (s, t, 1))
};

// A node of the bounding volume hierarchy: four children, their boxes quantized to a byte per
// plane as in CWBVH (Ylitie, Karras & Laine, "Efficient Incoherent Ray Traversal on GPUs Through
// Compressed Wide BVHs", HPG 2017), so that one 64-byte fetch tests four boxes. Child i's box is
// origin + q · scale per axis, q its byte i of lower* and upper*, scale 2^(e − 127) with e byte
// 0, 1, 2 of `scales` (x, y, z); the host rounds the planes outwards, so a box decoded holds its
// child. Byte i of `kinds`: WIDE_CHILD_EMPTY, WIDE_CHILD_INNER (children[i] is its node) or a
// leaf's primitive count (primitiveRefs[children[i] ..]).
struct PH_ALIGN16 WideBvhNode {
    vec3 origin; uint scales;
    uint lowerX; uint lowerY; uint lowerZ; uint kinds;
    uint upperX; uint upperY; uint upperZ; uint pad0;
    uvec4 children;
};

// A triangle that emits, for sampling the emissive triangles of a LIGHT_TRIANGLES light by power.
struct PH_ALIGN16 EmissiveTriangle {
    uint triangle; float cdf; float probability; float area;  // cdf: Σ probability up to and with this one
};

// A light of any type (LIGHT_*). Fields that mean different things for different types are read
// through the accessors of light_types.h, which say what each one is for each type.
struct PH_ALIGN16 Light {
    vec3 position; uint type;      // a point of the light (pointPosition, sphereCenter, quadCorner, ...)
    vec3 power; float extent;      // emitted flux Φ per channel [W]; a length (sphereRadius, boundingRadius)
    vec3 axis; float spotOuter;    // a unit direction (spotAxis, quadNormal, ...); spot: 1 - cos of the
                                   // cone's half-angle (kept as 1 - cos: exact for narrow beams)
    vec3 vectorU; float spotInner; // a vector (quadEdgeU, directionalIrradiance, environmentScale);
                                   // spot: 1 - cos of the angle where the falloff starts
    vec3 vectorV; float area;      // a vector (quadEdgeV); emitting area (sphere, quad)
    float pickCdf; float pickProbability; uint profile; float falloffMean;
    // pickCdf: Σ pickProbability of this and earlier lights; profile: EMIT_*;
    // falloffMean: mean of the spot falloff over its cone, normalises the intensity
    uint emitterFirst; uint emitterCount; float spanY; float spanZ;
    // LIGHT_TRIANGLES: its emissive triangles, emissiveTriangles[emitterFirst ..];
    // LIGHT_ENVIRONMENT: (area, spanY, spanZ) the half-extents of the scene's bounding box
};

// A bounding sphere of a specular object: the caustic pass emits photons towards these.
struct PH_ALIGN16 CausticTarget {
    vec3 center; float radius;
};

// ---- Per-frame parameters -------------------------------------------------------------------

struct PH_ALIGN16 Camera {
    vec3 position; float lensRadius;   // thin lens: 0 is a pinhole
    vec3 forward; float focusDistance;
    vec3 right; float tanHalfFovY;
    vec3 up; float aspect;             // width / height
};

struct PH_ALIGN16 SceneInfo {
    uint planeCount; uint lightCount; uint targetCount; uint infiniteLight;
    // lightCount: lights[0 .. lightCount) emit photons and are sampled for direct light;
    // infiniteLight: what rays that leave the scene see, infiniteLights[infiniteLight]
    uint bvhNodeCount; uint linearCount; uint environmentLight; uint medium;
    // environmentLight: the environment's index in lights when it lights the scene, else NONE;
    // medium: the Medium the camera and the lights are in, within its box (NONE: none);
    // bvhNodeCount 0: no hierarchy is traversed; linearCount: bounded primitives tested one by one
    // instead (a scene too small for a hierarchy to pay), primitiveRefs[0 .. linearCount)
    uint pad2; uint pad3; uint pad4; uint pad5;  // (FrameParams keeps its layout)
};

struct PH_ALIGN16 GridParams {
    vec3 origin; float cellSize;       // bounded: lower corner; both: cell edge length
    uint resolution; uint kind; uint cellCount; uint cellOffset;
    // resolution: bounded grid cells per axis (k); kind: GRID_*; cellCount: k³ or the table size
    // (a power of two); cellOffset: where this map's cells start in cellCounts/cellStart
    uint photonOffset; uint photonCapacity; float radius; uint pad0;
    // photonOffset/Capacity: this map's slice of the photon arrays; radius: query radius
};

// sppm's start and pass counting for one map (sppm.h).
struct PH_ALIGN16 SppmMapParams {
    float firstRadius; float firstFootprints; uint batches; uint firstNeighbours;
    // firstRadius: every pixel's first radius (0: from the photon density, sppmFirstRadius);
    // firstFootprints: the disc, in footprints, that would hold firstNeighbours photons if they
    // spread evenly over the image; batches: the photon passes this frame's photons of the map
    // count as
};

// The frame's wavelength set under FLAG_SPECTRAL (spectral.h): every path of the frame carries
// its radiance at these three wavelengths in the x, y and z of its vec3s.
struct PH_ALIGN16 SpectralParams {
    vec4 wavelengths;  // λ0, λ1, λ2 [nm]; w unused
    vec4 cauchy;       // (523655 / λi² - 1.5168) / 20: n(λi) = n_d + (n_d - 1) · dispersion · cauchy_i
    vec4 fromRgb0; vec4 fromRgb1; vec4 fromRgb2;  // row i: the spectral primaries' values at λi
    vec4 toRgb0; vec4 toRgb1; vec4 toRgb2;        // row c: linear sRGB channel c of the three samples
};

struct PH_ALIGN16 FrameParams {
    Camera camera;
    SceneInfo scene;
    GridParams grids[MAP_COUNT];
    SppmMapParams sppm[MAP_COUNT];
    uint width; uint height; uint frameIndex; uint seed;
    uint globalPaths; uint causticPaths; uint maxPhotonDepth; uint maxEyeDepth;
    // globalPaths/causticPaths: photons emitted this frame by the global and the caustic pass
    uint estimator; uint kernel; uint knnK; uint globalMode;
    uint gatherRays; uint lightSamples; uint view; uint flags;
    uint eyeSplits; uint accumulated; uint gatherBudget; float alpha;
    // eyeSplits: the interfaces where an eye path follows both branches (eye_trace.h);
    // accumulated: frames already averaged into the accumulation buffer (the progressive index i);
    // gatherBudget: photons a query visits per cell before it subsamples the cell (0: all);
    // alpha: sppm's α
    uint pathFirst; uint pathCount; float branchShrink; uint pad1;
    // the paths this renderer traces, [pathFirst, pathFirst + pathCount) of the frame's
    // globalPaths + causticPaths: all of them, or one rank's share when several GPUs split a frame;
    // branchShrink: how far the radii of eye-path branches without a hit point have shrunk by this
    // frame, as progressive photon mapping's (progressive.h; eye_trace.h)
    SpectralParams spectrum;
    Camera previousCamera;  // under FLAG_REPROJECT: the camera of the frame before (reproject.h)
};

// ---- Photon maps ------------------------------------------------------------------------------

// A photon as the photon pass records it.
struct PH_ALIGN16 Photon {
    vec3 position; uint incoming;  // octahedral-encoded unit direction towards where it came from
    vec3 power; uint id;           // flux [W]; (path << PHOTON_BOUNCE_BITS) | bounce, see photonId()
};

// A photon as the maps keep it for the estimates, in half the bytes (map_photon.h).
struct PH_ALIGN16 MapPhoton {
    uint x; uint y; uint z;
    // high 24 bits: the position's coordinate relative to the grid's origin, a float rounded to 15
    // mantissa bits; low 8 bits: one byte each of the 24-bit octahedral incoming direction
    uint power;  // Ward's RGBE: three 8-bit mantissas and a shared exponent in the top byte
};

// ---- Eye pass ---------------------------------------------------------------------------------

// Where a pixel's eye path ended on a non-specular surface, and what it already knows.
struct PH_ALIGN16 HitPoint {
    vec3 position; uint material;    // material NONE: the path ended elsewhere, `direct` is all
    vec3 weight; uint normal;        // path throughput from the camera; octahedral shading normal facing ωo
    vec3 direct; uint outgoing;      // weighted emission, background and direct light; octahedral ωo
    vec3 albedo; uint geometricNormal;  // the albedo there (textured); octahedral geometric normal facing ωo
    float metallic; float roughness; uint channel; float pathLength;
    // pbr: textured metallic and GGX α there; channel: the one wavelength of the frame's three the
    // path kept at a dispersive surface (CHANNEL_ALL: none met), spectral.h; pathLength: the eye
    // path's length from the camera to the surface of the auxiliary images (eye_trace.h,
    // meetAovSurface), through mirrors and glass (the depth of what a mirror shows); ≤ 0: none
    vec3 aovAlbedo; uint aovNormal;  // that surface's albedo (RGB, times the path's weight) and octahedral shading normal
};

// A pixel's statistics under stochastic progressive photon mapping (sppm.h), kept across frames:
// for each map the flux τ, the radius R and the photon count N; and the mean of the direct part.
struct PH_ALIGN16 SppmFlux {
    vec3 flux; float radius;
};

struct PH_ALIGN16 SppmPixel {
    vec3 direct; float pad0;            // mean over frames of emission, background and direct light
    SppmFlux maps[SURFACE_MAP_COUNT];
    float count[SPPM_COUNT_SLOTS];      // N of each map (the slots beyond SURFACE_MAP_COUNT unused)
};

// A pixel's auxiliary images (aov.h), running means over the frames since the last reset, as
// Open Image Denoise defines them: the albedo and shading normal where the eye path ended (after
// mirrors and glass), and the depth of the camera ray's first hit.
struct PH_ALIGN16 PixelAov {
    vec3 albedo; float depth;      // reflectance at the path's end (times the path's weight); its path length, among frames that end on a surface
    vec3 normal; float coverage;   // mean shading normal (0 where paths escape); share of frames whose path ended on a surface
    float luminance; float luminance2; float frames; float pad1;
    // luminance, luminance2: moments of the frames' luminance (denoise.h's variance); frames: how
    // many frames these means hold, the pixel's history (history.h)
    vec3 background; float pad2;   // mean radiance of the frames whose path met no such surface (emitters, the sky)
};

// A pixel's means as the frame before left them, set aside by the reproject stage's first pass so
// that its second can move them to where the camera now sees the same surface (reproject.h).
struct PH_ALIGN16 HistoryPixel {
    SppmPixel sppm;     // under the sppm estimator
    vec4 accumulation;
    PixelAov aov;
};

PH_NAMESPACE_END

#ifdef __cplusplus
namespace photon {
PH_SIZE(PixelAov, 64); PH_OFFSET(PixelAov, background, 48); PH_OFFSET(PixelAov, depth, 12); PH_OFFSET(PixelAov, normal, 16);
PH_OFFSET(PixelAov, coverage, 28); PH_OFFSET(PixelAov, luminance, 32); PH_OFFSET(PixelAov, luminance2, 36);
PH_OFFSET(PixelAov, frames, 40);
PH_SIZE(HistoryPixel, 16 + SURFACE_MAP_COUNT * 16 + 4 * SPPM_COUNT_SLOTS + 16 + 64); PH_OFFSET(HistoryPixel, sppm, 0);
PH_OFFSET(HistoryPixel, accumulation, 16 + SURFACE_MAP_COUNT * 16 + 4 * SPPM_COUNT_SLOTS);
PH_OFFSET(HistoryPixel, aov, 16 + SURFACE_MAP_COUNT * 16 + 4 * SPPM_COUNT_SLOTS + 16);
PH_SIZE(Sphere, 32); PH_OFFSET(Sphere, radius, 12); PH_OFFSET(Sphere, material, 16);
PH_SIZE(Plane, 32); PH_OFFSET(Plane, offset, 12); PH_OFFSET(Plane, material, 16);
PH_SIZE(Quad, 64); PH_OFFSET(Quad, material, 12); PH_OFFSET(Quad, edgeU, 16); PH_OFFSET(Quad, area, 28);
PH_OFFSET(Quad, edgeV, 32); PH_OFFSET(Quad, w, 48);
PH_SIZE(Triangle, 48); PH_OFFSET(Triangle, material, 12); PH_OFFSET(Triangle, v1, 16);
PH_OFFSET(Triangle, attributes, 28); PH_OFFSET(Triangle, v2, 32); PH_OFFSET(Triangle, flags, 44);
PH_SIZE(TriangleAttributes, 48); PH_OFFSET(TriangleAttributes, flags, 12); PH_OFFSET(TriangleAttributes, s0, 16);
PH_OFFSET(TriangleAttributes, t2, 36); PH_OFFSET(TriangleAttributes, tangent, 40);
PH_SIZE(Material, 112); PH_OFFSET(Material, type, 12); PH_OFFSET(Material, specular, 16);
PH_OFFSET(Material, roughness, 28); PH_OFFSET(Material, emission, 32); PH_OFFSET(Material, ior, 44);
PH_OFFSET(Material, albedoTexture, 48); PH_OFFSET(Material, emissionTexture, 60); PH_OFFSET(Material, metallic, 64);
PH_OFFSET(Material, alphaCutoff, 76); PH_OFFSET(Material, attenuation, 80); PH_OFFSET(Material, flags, 92);
PH_OFFSET(Material, normalScale, 96); PH_OFFSET(Material, dispersion, 100); PH_OFFSET(Material, medium, 104);
PH_SIZE(Medium, 80); PH_OFFSET(Medium, g, 12); PH_OFFSET(Medium, scattering, 16); PH_OFFSET(Medium, grid, 28);
PH_OFFSET(Medium, lower, 32); PH_OFFSET(Medium, upper, 48); PH_OFFSET(Medium, resolution, 64);
PH_SIZE(Texture, 48); PH_OFFSET(Texture, wrap, 12); PH_OFFSET(Texture, transformS, 16); PH_OFFSET(Texture, transformT, 32);
PH_SIZE(WideBvhNode, 64); PH_OFFSET(WideBvhNode, scales, 12); PH_OFFSET(WideBvhNode, lowerX, 16);
PH_OFFSET(WideBvhNode, kinds, 28); PH_OFFSET(WideBvhNode, upperX, 32); PH_OFFSET(WideBvhNode, pad0, 44);
PH_OFFSET(WideBvhNode, children, 48);
PH_SIZE(EmissiveTriangle, 16); PH_OFFSET(EmissiveTriangle, area, 12);
PH_SIZE(Light, 112); PH_OFFSET(Light, emitterFirst, 96); PH_OFFSET(Light, emitterCount, 100); PH_OFFSET(Light, type, 12); PH_OFFSET(Light, power, 16); PH_OFFSET(Light, extent, 28);
PH_OFFSET(Light, axis, 32); PH_OFFSET(Light, spotOuter, 44); PH_OFFSET(Light, vectorU, 48);
PH_OFFSET(Light, spotInner, 60); PH_OFFSET(Light, vectorV, 64); PH_OFFSET(Light, area, 76);
PH_OFFSET(Light, pickCdf, 80); PH_OFFSET(Light, pickProbability, 84); PH_OFFSET(Light, profile, 88);
PH_OFFSET(Light, falloffMean, 92);
PH_SIZE(CausticTarget, 16); PH_OFFSET(CausticTarget, radius, 12);
PH_SIZE(Camera, 64); PH_OFFSET(Camera, lensRadius, 12); PH_OFFSET(Camera, forward, 16);
PH_OFFSET(Camera, focusDistance, 28); PH_OFFSET(Camera, right, 32); PH_OFFSET(Camera, tanHalfFovY, 44);
PH_OFFSET(Camera, up, 48); PH_OFFSET(Camera, aspect, 60);
PH_SIZE(SceneInfo, 48); PH_OFFSET(SceneInfo, lightCount, 4); PH_OFFSET(SceneInfo, targetCount, 8);
PH_OFFSET(SceneInfo, infiniteLight, 12); PH_OFFSET(SceneInfo, bvhNodeCount, 16); PH_OFFSET(SceneInfo, linearCount, 20);
PH_OFFSET(SceneInfo, environmentLight, 24); PH_OFFSET(SceneInfo, medium, 28);
PH_SIZE(GridParams, 48); PH_OFFSET(GridParams, cellSize, 12); PH_OFFSET(GridParams, resolution, 16);
PH_OFFSET(GridParams, cellOffset, 28); PH_OFFSET(GridParams, photonOffset, 32);
PH_OFFSET(GridParams, radius, 40); PH_OFFSET(GridParams, pad0, 44);
PH_SIZE(SppmMapParams, 16); PH_OFFSET(SppmMapParams, batches, 8);
PH_SIZE(SpectralParams, 128); PH_OFFSET(SpectralParams, cauchy, 16); PH_OFFSET(SpectralParams, toRgb0, 80);
PH_SIZE(FrameParams, 64 + 48 + MAP_COUNT * (48 + 16) + 6 * 16 + 128 + 64); PH_OFFSET(FrameParams, scene, 64);
PH_OFFSET(FrameParams, grids, 112); PH_OFFSET(FrameParams, sppm, 112 + MAP_COUNT * 48);
PH_OFFSET(FrameParams, width, 112 + MAP_COUNT * 64);
PH_OFFSET(FrameParams, globalPaths, 128 + MAP_COUNT * 64); PH_OFFSET(FrameParams, estimator, 144 + MAP_COUNT * 64);
PH_OFFSET(FrameParams, gatherRays, 160 + MAP_COUNT * 64); PH_OFFSET(FrameParams, eyeSplits, 176 + MAP_COUNT * 64);
PH_OFFSET(FrameParams, alpha, 188 + MAP_COUNT * 64); PH_OFFSET(FrameParams, pathFirst, 192 + MAP_COUNT * 64);
PH_OFFSET(FrameParams, spectrum, 208 + MAP_COUNT * 64);
PH_OFFSET(FrameParams, previousCamera, 336 + MAP_COUNT * 64);
PH_SIZE(SppmFlux, 16); PH_OFFSET(SppmFlux, radius, 12);
PH_SIZE(SppmPixel, 16 + SURFACE_MAP_COUNT * 16 + 4 * SPPM_COUNT_SLOTS); PH_OFFSET(SppmPixel, maps, 16);
PH_OFFSET(SppmPixel, count, 16 + SURFACE_MAP_COUNT * 16);
static_assert(SURFACE_MAP_COUNT <= SPPM_COUNT_SLOTS && MAP_VOLUME == SURFACE_MAP_COUNT, "SppmPixel::count holds a slot per surface map");
PH_SIZE(Photon, 32); PH_OFFSET(Photon, incoming, 12); PH_OFFSET(Photon, power, 16); PH_OFFSET(Photon, id, 28);
PH_SIZE(MapPhoton, 16); PH_OFFSET(MapPhoton, power, 12);
PH_SIZE(HitPoint, 96); PH_OFFSET(HitPoint, aovAlbedo, 80); PH_OFFSET(HitPoint, aovNormal, 92); PH_OFFSET(HitPoint, metallic, 64); PH_OFFSET(HitPoint, channel, 72); PH_OFFSET(HitPoint, roughness, 68); PH_OFFSET(HitPoint, material, 12); PH_OFFSET(HitPoint, weight, 16);
PH_OFFSET(HitPoint, normal, 28); PH_OFFSET(HitPoint, direct, 32); PH_OFFSET(HitPoint, outgoing, 44);
PH_OFFSET(HitPoint, albedo, 48); PH_OFFSET(HitPoint, geometricNormal, 60); PH_OFFSET(HitPoint, pathLength, 76);
}  // namespace photon
#endif

#endif
