// A scene on the host: the shared buffer structs in vectors, plus the camera and render settings.
// Built by the JSON loader or directly by code (tests), then finalize()d before rendering.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/bvh.h"
#include "core/scene/density_grid.h"
#include "core/scene/environment.h"
#include "core/scene/mesh.h"
#include "core/settings/settings.h"
#include "shared/bindings.h"

namespace photon {

struct CameraDesc {
    glm::vec3 position{0.0f, 0.0f, 5.0f};
    glm::vec3 lookAt{0.0f, 0.0f, 0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovY = 40.0f;          // vertical field of view, degrees
    float lensRadius = 0.0f;     // thin lens; 0 is a pinhole
    float focusDistance = 0.0f;  // 0: the distance to lookAt
};

Material makeDiffuse(glm::vec3 albedo);
Material makeMirror(glm::vec3 reflectance);
Material makeGlass(float ior, glm::vec3 tint);
Material makeGlossy(glm::vec3 albedo, glm::vec3 specular, float roughness);  // roughness = GGX α
Material makeReflective(glm::vec3 albedo, glm::vec3 reflectance);  // Lambertian under a mirror coat
Material makeEmitter(glm::vec3 radiance);
// glTF's metallic-roughness material (shared/pbr.h), ior 1.5, opaque; roughness is perceptual (α = roughness²).
Material makePbr(glm::vec3 baseColor, float metallic, float roughness);

// The rows of shared/bindings.h whose size is SCENE: one host array each, named as the buffer.
#define PH_SCENE_ONLY_SCENE(...) __VA_ARGS__
#define PH_SCENE_ONLY_PHOTON(...)
#define PH_SCENE_ONLY_CELL(...)
#define PH_SCENE_ONLY_PIXEL(...)
#define PH_SCENE_ONLY_COUNTER(...)
#define PH_SCENE_ONLY_SPPM_PIXEL(...)
#define PH_SCENE_ONLY_ORDERED_PHOTON(...)
#define PH_SCENE_ONLY_AOV_PIXEL(...)
#define PH_SCENE_ONLY_DENOISE_PIXEL(...)
#define PH_SCENE_ONLY_DENOISE_PLANE(...)
#define PH_SCENE_ONLY_HISTORY_PIXEL(...)
#define PH_SCENE_VECTOR(NAME, b, T, name, access, sizeClass) PH_SCENE_ONLY_##sizeClass(std::vector<T> name;)

// Triangles that came in as one object (a mesh, or a scene file's triangle): the caustic pass aims
// at each object's casters as a whole.
struct TriangleObject {
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};

// The widest scene Photon renders (along any axis, scene units): its query radii, grid cells and
// areas (a span squared) stay within floats. The loaders refuse wider models and scenes by name.
inline constexpr double kMaxSceneSpan = 1e15;

// The box of a medium that no box bounds (an object's: the object bounds it).
inline constexpr float kMediumUnbounded = 1e30f;

// A homogeneous medium without coefficients yet, unbounded (its density 1 everywhere: no grid).
inline Medium homogeneousMedium() {
    Medium md{};
    md.grid = NONE;
    md.lower = glm::vec3(-kMediumUnbounded);
    md.upper = glm::vec3(kMediumUnbounded);
    return md;
}

// "1e+30 wide (z from 0 to 1e+30)": the widest axis of a box, for messages.
std::string describeSpan(glm::vec3 lo, glm::vec3 hi);
double widestSpan(glm::vec3 lo, glm::vec3 hi);

struct Scene {
    std::string name;
    // The shared arrays: spheres, planes, quads, triangles with their attributes, materials,
    // textures and texels, lights; and by finalize(): the emissive triangles, the caustic targets
    // (bounding spheres of the bounded casters), the BVH nodes and primitive references.
    PH_BUFFERS(PH_SCENE_VECTOR)
    std::vector<std::string> materialNames;
    std::vector<TriangleObject> objects;
    CameraDesc camera;
    // What rays that leave the scene see (by default black, lighting nothing); set it with
    // setEnvironment(), which builds its map's distribution into environmentTexels and environmentCdf.
    EnvironmentLight environment;
    glm::dvec3 environmentIntegral{0.0};  // ∫ map texel dω (setEnvironment)
    double environmentBuildSeconds = 0.0;  // setEnvironment's time for the map's texels and cdfs
    std::uint32_t environmentLight = NONE;  // by finalize(): the environment's index in lights, if it lights
    std::uint32_t medium = NONE;  // the medium the camera and lights are in, within its box (media)
    glm::vec3 boundsMin{0.0f};  // by finalize()
    glm::vec3 boundsMax{0.0f};
    RenderSettings render;
    std::uint64_t droppedTriangles = 0;  // of meshes: zero area or not finite
    // What the loaders noticed and the user should hear of, one line each naming the file (and
    // the place in it): triangles dropped, a model lit by the studio because its own lights are weak.
    std::vector<std::string> warnings;
    BvhStats bvh;                        // by finalize()

    std::uint32_t addMaterial(const std::string& materialName, const Material& m);
    // Index of a material by name, or NONE.
    std::uint32_t findMaterial(const std::string& materialName) const;

    void addSphere(glm::vec3 center, float radius, std::uint32_t material);
    void addPlane(glm::vec3 point, glm::vec3 normal, std::uint32_t material);
    void addQuad(glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, std::uint32_t material);
    void addTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, std::uint32_t material);
    // The mesh's triangles, transformed (normals by the inverse transpose; a mirroring transform
    // keeps each triangle's front), as one object. Triangles without area are dropped and counted.
    void addMesh(const Mesh& mesh, const glm::mat4& transform);
    // A participating medium (shared/medium.h); its index, for Material::medium or fillWithMedium.
    // Homogeneous unless m.grid names a grid of addDensityGrid.
    std::uint32_t addMedium(const Medium& m);
    // The voxels of a heterogeneous medium's density (shared/medium_grid.h) into `densities`; the
    // index of the first, for Medium::grid with the grid's resolution and box. Throws InputError
    // when the scene's grids together would pass kDensityVoxelsMax.
    std::uint32_t addDensityGrid(const DensityGrid& grid);
    // The scene is filled with medium `index` within its box; an unbounded box becomes the scene's
    // bounds (finalize()), so that photons and rays leaving the scene leave the medium too.
    void fillWithMedium(std::uint32_t index);
    // A texture of linear RGBA texels (16 bits a channel, packed as in shared/texture.h); its index.
    std::uint32_t addTexture(std::uint32_t width, std::uint32_t height, std::vector<glm::uvec2> linearTexels,
                             std::uint32_t wrapS, std::uint32_t wrapT);
    // The texels of `texture` seen through a transform of the texture coordinates
    // (s' = transformS · (s, t, 1), t' likewise; KHR_texture_transform); its index.
    std::uint32_t addTextureView(std::uint32_t texture, glm::vec3 transformS, glm::vec3 transformT);

    // Lights; power is the emitted flux in watts per channel. Area lights also add their visible
    // surface, with an emitter material of radiance Φ / (π · area).
    void addPointLight(glm::vec3 position, glm::vec3 power);
    void addHemisphereLight(glm::vec3 position, glm::vec3 axis, glm::vec3 power);
    void addSpotLight(glm::vec3 position, glm::vec3 direction, glm::vec3 power, float outerDegrees,
                      float innerDegrees);
    void addSphereLight(glm::vec3 center, float radius, glm::vec3 power);
    void addQuadLight(glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, glm::vec3 power);
    // Parallel light travelling along `direction`, of irradiance E [W/m² per channel] on a surface
    // facing it (the sun). finalize() sizes it to the scene's bounds.
    void addDirectionalLight(glm::vec3 direction, glm::vec3 irradiance);
    // The environment (one a scene); finalize() makes its light, and adds it to `lights` if it
    // lights and emits anything.
    void setEnvironment(EnvironmentLight light);
    // A uniform environment of `radiance` that only colours what the camera sees (the scene
    // format's `background`).
    void setBackground(glm::vec3 radiance);

    // Where light `light` is for someone moving it (a directional light: a point on its side of
    // the scene, out of the bounds), and moving it by delta with what belongs to it: the surface
    // of a sphere or quad light, the triangles of the emissive triangles' light; a directional
    // light turns to shine from its moved point. Call finalize() after.
    glm::vec3 lightHandle(std::uint32_t light) const;
    void moveLight(std::uint32_t light, glm::vec3 delta);

    // Bounds, the emissive triangles' light, the environment's light, light pick probabilities,
    // caustic targets and the BVH.
    // Call after the last add*() (again after any change).
    void finalize();

    float diagonal() const;
    bool hasCausticTargets() const { return !targets.empty(); }
    // Whether any surface reflects or refracts specularly (a caster or a mirror coat): only then
    // can a photon path be a caustic one.
    bool makesCausticPaths() const;
};

// "point", "spot", ..., for people: the name of a LIGHT_* type.
const char* lightTypeName(std::uint32_t type);

// A scene array by binding (any row of size SCENE): its elements, or nullptr for other rows.
struct HostArray {
    const void* data = nullptr;
    std::size_t count = 0;
};
HostArray sceneArray(const Scene& scene, std::uint32_t binding);

// A light of `type` at `position` emitting `power`, its other fields zero (an isotropic profile).
Light emptyLight(std::uint32_t type, glm::vec3 position, glm::vec3 power);

// The shared camera for an image of width × height.
Camera makeCamera(const CameraDesc& desc, std::uint32_t width, std::uint32_t height);

// Points the scene members of host-side Bindings at the scene's arrays, for running shared/
// functions on the CPU.
void bindSceneArrays(Bindings& bindings, const Scene& scene);

}  // namespace photon
