#include "core/scene/scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "core/system/error.h"
#include "core/system/parallel.h"
#include "shared/light_types.h"
#include "shared/material.h"

#include <glm/gtc/matrix_transform.hpp>

namespace photon {
namespace {

// 1 - cos θ for θ in degrees, as 2 sin²(θ/2): exact for tiny angles.
float oneMinusCosDegrees(double degrees) {
    double s = std::sin(0.5 * degrees * 3.14159265358979323846 / 180.0);
    return static_cast<float>(2.0 * s * s);
}

// A material of `type` with nothing set: no texture (texture 0 is a real texture), index of
// refraction 1.
Material blankMaterial(std::uint32_t type) {
    Material m{};
    m.type = type;
    m.albedoTexture = NONE;
    m.metallicRoughnessTexture = NONE;
    m.normalTexture = NONE;
    m.emissionTexture = NONE;
    m.medium = NONE;
    m.ior = 1.0f;
    m.alpha = 1.0f;
    m.alphaCutoff = 0.5f;
    m.normalScale = 1.0f;
    return m;
}

// The unit tangent ∂p/∂s of triangle (p0, p1, p2) with texture coordinates (c0, c1, c2), and
// whether the bitangent n × t points against −∂p/∂t (a mirrored mapping; t runs down the image, so
// n × t points up it). False where the coordinates are degenerate.
bool triangleTangent(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec2 c0, glm::vec2 c1, glm::vec2 c2,
                     glm::vec3& tangent, bool& flipped) {
    glm::vec3 e1 = p1 - p0;
    glm::vec3 e2 = p2 - p0;
    glm::vec2 d1 = c1 - c0;
    glm::vec2 d2 = c2 - c0;
    float det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(det) > 1e-20f)) {
        return false;
    }
    glm::vec3 dpds = (e1 * d2.y - e2 * d1.y) / det;
    glm::vec3 dpdt = (e2 * d1.x - e1 * d2.x) / det;
    float length = glm::length(dpds);
    if (!(length > 0.0f) || !std::isfinite(length)) {
        return false;
    }
    tangent = dpds / length;
    flipped = glm::dot(glm::cross(glm::cross(e1, e2), tangent), -dpdt) < 0.0f;
    return true;
}

// Moves each shape of `material` (none for NONE) by `delta`, through its anchor point.
template <typename Shape>
void moveShapesOf(std::vector<Shape>& shapes, glm::vec3 Shape::*anchor, std::uint32_t material, glm::vec3 delta) {
    for (Shape& shape : shapes) {
        if (material != NONE && shape.material == material) {
            shape.*anchor += delta;
        }
    }
}

}  // namespace

Light emptyLight(std::uint32_t type, glm::vec3 position, glm::vec3 power) {
    Light l{};
    l.type = type;
    l.position = position;
    l.power = power;
    l.axis = glm::vec3(0.0f, 0.0f, 1.0f);
    l.profile = EMIT_ISOTROPIC;
    l.falloffMean = 1.0f;
    return l;
}

Material makePbr(glm::vec3 baseColor, float metallic, float roughness) {
    Material m = blankMaterial(MATERIAL_PBR);
    m.albedo = baseColor;
    m.metallic = metallic;
    m.roughness = roughness * roughness;
    m.ior = 1.5f;
    return m;
}

Material makeDiffuse(glm::vec3 albedo) {
    Material m = blankMaterial(MATERIAL_DIFFUSE);
    m.albedo = albedo;
    return m;
}

Material makeMirror(glm::vec3 reflectance) {
    Material m = blankMaterial(MATERIAL_MIRROR);
    m.specular = reflectance;
    return m;
}

Material makeGlass(float ior, glm::vec3 tint) {
    Material m = blankMaterial(MATERIAL_GLASS);
    m.specular = tint;
    m.ior = ior;
    return m;
}

Material makeGlossy(glm::vec3 albedo, glm::vec3 specular, float roughness) {
    Material m = blankMaterial(MATERIAL_GLOSSY);
    m.albedo = albedo;
    m.specular = specular;
    m.roughness = roughness;
    return m;
}

Material makeReflective(glm::vec3 albedo, glm::vec3 reflectance) {
    Material m = blankMaterial(MATERIAL_REFLECTIVE);
    m.albedo = albedo;
    m.specular = reflectance;
    return m;
}

Material makeEmitter(glm::vec3 radiance) {
    Material m = blankMaterial(MATERIAL_EMITTER);
    m.emission = radiance;
    return m;
}

std::uint32_t Scene::addMaterial(const std::string& materialName, const Material& m) {
    materials.push_back(m);
    materialNames.push_back(materialName);
    return static_cast<std::uint32_t>(materials.size() - 1);
}

std::uint32_t Scene::addMedium(const Medium& m) {
    media.push_back(m);
    return static_cast<std::uint32_t>(media.size() - 1);
}

std::uint32_t Scene::addDensityGrid(const DensityGrid& grid) {
    std::uint64_t voxels = std::uint64_t(grid.resolution.x) * grid.resolution.y * grid.resolution.z;
    if (voxels == 0 || voxels != grid.density.size()) {
        throw InputError("a density grid of " + std::to_string(grid.density.size()) + " voxels for " +
                         std::to_string(voxels) + " places");
    }
    if (densities.size() + voxels > kDensityVoxelsMax) {
        throw InputError("the scene's density grids hold " + std::to_string(densities.size() + voxels) +
                         " voxels, more than " + std::to_string(kDensityVoxelsMax));
    }
    std::uint32_t first = static_cast<std::uint32_t>(densities.size());
    densities.insert(densities.end(), grid.density.begin(), grid.density.end());
    return first;
}

void Scene::fillWithMedium(std::uint32_t index) { medium = index; }

std::uint32_t Scene::findMaterial(const std::string& materialName) const {
    auto it = std::find(materialNames.begin(), materialNames.end(), materialName);
    return it == materialNames.end() ? NONE : static_cast<std::uint32_t>(it - materialNames.begin());
}

void Scene::addSphere(glm::vec3 center, float radius, std::uint32_t material) {
    Sphere s{};
    s.center = center;
    s.radius = radius;
    s.material = material;
    spheres.push_back(s);
}

void Scene::addPlane(glm::vec3 point, glm::vec3 normal, std::uint32_t material) {
    Plane p{};
    p.normal = glm::normalize(normal);
    p.offset = glm::dot(p.normal, point);
    p.material = material;
    planes.push_back(p);
}

void Scene::addQuad(glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, std::uint32_t material) {
    Quad q{};
    q.corner = corner;
    q.edgeU = edgeU;
    q.edgeV = edgeV;
    q.material = material;
    glm::vec3 n = glm::cross(edgeU, edgeV);
    q.area = glm::length(n);
    q.w = n / glm::dot(n, n);
    quads.push_back(q);
}

void Scene::addTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, std::uint32_t material) {
    Triangle t{};
    t.v0 = a;
    t.v1 = b;
    t.v2 = c;
    t.material = material;
    t.attributes = NONE;
    t.flags = 0u;
    objects.push_back({std::uint32_t(triangles.size()), 1});
    triangles.push_back(t);
}

glm::mat4 composeTransform(glm::vec3 scale, float rotateDegrees, glm::vec3 axis, glm::vec3 translate) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translate);
    if (rotateDegrees != 0.0f) {
        m = glm::rotate(m, glm::radians(rotateDegrees), glm::normalize(axis));
    }
    return glm::scale(m, scale);
}

void Scene::addMesh(const Mesh& mesh, const glm::mat4& transform) {
    glm::mat3 normalTransform = glm::transpose(glm::inverse(glm::mat3(transform)));
    bool mirrors = glm::determinant(glm::mat3(transform)) < 0.0f;
    bool hasNormals = mesh.normals.size() == mesh.positions.size() && !mesh.normals.empty();
    bool hasTexcoords = mesh.texcoords.size() == mesh.positions.size() && !mesh.texcoords.empty();
    bool hasTangents = hasTexcoords && mesh.tangents.size() == mesh.positions.size();
    bool attributed = hasNormals || hasTexcoords;
    // Vertices into the scene's space, normals by the inverse transpose.
    std::vector<glm::vec3> world(mesh.positions.size());
    std::vector<std::uint32_t> normals(hasNormals ? mesh.normals.size() : 0);
    std::vector<std::uint8_t> usableNormal(normals.size());
    parallelFor(world.size(), 65536, [&](std::size_t a, std::size_t b) {
        for (std::size_t i = a; i < b; ++i) {
            world[i] = glm::vec3(transform * glm::vec4(mesh.positions[i], 1.0f));
            if (hasNormals) {
                glm::vec3 n = normalTransform * mesh.normals[i];
                float length = glm::length(n);
                usableNormal[i] = std::isfinite(length) && length > 0.0f;
                normals[i] = usableNormal[i] ? octEncode(n / length) : 0u;
            }
        }
    });
    // Which triangles have an area (in chunks, counted first, so that they keep their order).
    std::size_t count = mesh.triangles.size();
    std::vector<std::uint8_t> keep(count);
    constexpr std::size_t kChunk = 65536;
    std::size_t chunks = (count + kChunk - 1) / kChunk;
    std::vector<std::size_t> kept(chunks + 1, 0);
    parallelFor(chunks, 1, [&](std::size_t a, std::size_t b) {
        for (std::size_t c = a; c < b; ++c) {
            for (std::size_t f = c * kChunk; f < std::min(count, (c + 1) * kChunk); ++f) {
                glm::uvec3 v = mesh.triangles[f];
                glm::vec3 e1 = world[v.y] - world[v.x];
                glm::vec3 e2 = world[v.z] - world[v.x];
                glm::vec3 n = glm::cross(e1, e2);
                float area2 = glm::dot(n, n);
                float scale2 = glm::dot(e1, e1) * glm::dot(e2, e2);
                keep[f] = area2 > 1e-14f * scale2 && std::isfinite(area2) && std::isfinite(scale2);
                kept[c + 1] += keep[f];
            }
        }
    });
    for (std::size_t c = 0; c < chunks; ++c) {
        kept[c + 1] += kept[c];
    }
    std::size_t firstTriangle = triangles.size();
    std::size_t firstAttributes = triangleAttributes.size();
    triangles.resize(firstTriangle + kept[chunks]);
    if (attributed) {
        triangleAttributes.resize(firstAttributes + kept[chunks]);
    }
    parallelFor(chunks, 1, [&](std::size_t a, std::size_t b) {
        for (std::size_t c = a; c < b; ++c) {
            std::size_t out = kept[c];
            for (std::size_t f = c * kChunk; f < std::min(count, (c + 1) * kChunk); ++f) {
                if (!keep[f]) {
                    continue;
                }
                glm::uvec3 v = mesh.triangles[f];
                if (mirrors) {
                    std::swap(v.y, v.z);  // a mirror image reverses the winding: keep the front the front
                }
                Triangle& t = triangles[firstTriangle + out];
                t.v0 = world[v.x];
                t.v1 = world[v.y];
                t.v2 = world[v.z];
                t.material = mesh.materials[f];
                t.attributes = NONE;
                t.flags = 0u;
                if (attributed) {
                    TriangleAttributes attributes{};
                    if (hasNormals && usableNormal[v.x] && usableNormal[v.y] && usableNormal[v.z]) {
                        attributes.normal0 = normals[v.x];
                        attributes.normal1 = normals[v.y];
                        attributes.normal2 = normals[v.z];
                        attributes.flags |= ATTRIBUTE_NORMALS;
                    }
                    if (hasTexcoords) {
                        attributes.s0 = mesh.texcoords[v.x].x;
                        attributes.t0 = mesh.texcoords[v.x].y;
                        attributes.s1 = mesh.texcoords[v.y].x;
                        attributes.t1 = mesh.texcoords[v.y].y;
                        attributes.s2 = mesh.texcoords[v.z].x;
                        attributes.t2 = mesh.texcoords[v.z].y;
                        attributes.flags |= ATTRIBUTE_TEXCOORDS;
                        glm::vec3 tangent;
                        bool flipped = false;
                        if (hasTangents) {
                            // The file's (MikkTSpace) tangents, as a direction: by the transform itself.
                            glm::vec4 sum = mesh.tangents[v.x] + mesh.tangents[v.y] + mesh.tangents[v.z];
                            tangent = glm::mat3(transform) * glm::vec3(sum);
                            flipped = (sum.w < 0.0f) != mirrors;
                        }
                        bool usable = hasTangents && std::isfinite(glm::length(tangent)) && glm::length(tangent) > 0.0f;
                        if (!usable) {
                            usable = triangleTangent(t.v0, t.v1, t.v2, mesh.texcoords[v.x], mesh.texcoords[v.y],
                                                     mesh.texcoords[v.z], tangent, flipped);
                        }
                        if (usable) {
                            attributes.tangent = octEncode(glm::normalize(tangent));
                            attributes.flags |= ATTRIBUTE_TANGENT | (flipped ? ATTRIBUTE_FLIPPED_BITANGENT : 0u);
                        }
                    }
                    t.attributes = std::uint32_t(firstAttributes + out);
                    triangleAttributes[firstAttributes + out] = attributes;
                }
                out += 1;
            }
        }
    });
    droppedTriangles += count - kept[chunks];
    if (kept[chunks] > 0) {
        objects.push_back({std::uint32_t(firstTriangle), std::uint32_t(kept[chunks])});
    }
}

std::uint32_t Scene::addTextureView(std::uint32_t texture, glm::vec3 transformS, glm::vec3 transformT) {
    Texture t = textures.at(texture);
    t.transformS = transformS;
    t.transformT = transformT;
    textures.push_back(t);
    return std::uint32_t(textures.size() - 1);
}

std::uint32_t Scene::addTexture(std::uint32_t width, std::uint32_t height, std::vector<glm::uvec2> linearTexels,
                                std::uint32_t wrapS, std::uint32_t wrapT) {
    Texture t{};
    t.offset = std::uint32_t(texels.size());
    t.width = width;
    t.height = height;
    t.wrap = wrapS | (wrapT << 4u);
    t.transformS = glm::vec3(1.0f, 0.0f, 0.0f);
    t.transformT = glm::vec3(0.0f, 1.0f, 0.0f);
    texels.insert(texels.end(), linearTexels.begin(), linearTexels.end());
    textures.push_back(t);
    return std::uint32_t(textures.size() - 1);
}

void Scene::addPointLight(glm::vec3 position, glm::vec3 power) {
    lights.push_back(emptyLight(LIGHT_POINT, position, power));
}

void Scene::addHemisphereLight(glm::vec3 position, glm::vec3 axis, glm::vec3 power) {
    Light l = emptyLight(LIGHT_POINT, position, power);
    l.profile = EMIT_HEMISPHERE;
    l.axis = glm::normalize(axis);
    lights.push_back(l);
}

void Scene::addSpotLight(glm::vec3 position, glm::vec3 direction, glm::vec3 power, float outerDegrees,
                         float innerDegrees) {
    Light l = emptyLight(LIGHT_SPOT, position, power);
    l.axis = glm::normalize(direction);
    l.spotOuter = oneMinusCosDegrees(outerDegrees);
    l.spotInner = std::min(oneMinusCosDegrees(innerDegrees), l.spotOuter);
    // Directions are uniform in 1 - cosθ over [0, outer]; the smoothstep ramp averages 1/2.
    l.falloffMean = (l.spotInner + 0.5f * (l.spotOuter - l.spotInner)) / l.spotOuter;
    lights.push_back(l);
}

void Scene::addSphereLight(glm::vec3 center, float radius, glm::vec3 power) {
    Light l = emptyLight(LIGHT_SPHERE, center, power);
    l.extent = radius;
    l.area = 4.0f * PI * radius * radius;
    lights.push_back(l);
    std::uint32_t m = addMaterial("light" + std::to_string(lights.size() - 1), makeEmitter(power * (INV_PI / l.area)));
    addSphere(center, radius, m);
}

void Scene::addDirectionalLight(glm::vec3 direction, glm::vec3 irradiance) {
    Light l = emptyLight(LIGHT_DIRECTIONAL, glm::vec3(0.0f), irradiance);
    l.axis = glm::normalize(direction);
    l.vectorU = irradiance;
    lights.push_back(l);
}

void Scene::addQuadLight(glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, glm::vec3 power) {
    Light l = emptyLight(LIGHT_QUAD, corner, power);
    l.vectorU = edgeU;
    l.vectorV = edgeV;
    glm::vec3 n = glm::cross(edgeU, edgeV);
    l.area = glm::length(n);
    l.axis = n / l.area;
    lights.push_back(l);
    std::uint32_t m = addMaterial("light" + std::to_string(lights.size() - 1), makeEmitter(power * (INV_PI / l.area)));
    addQuad(corner, edgeU, edgeV, m);
}

const char* lightTypeName(std::uint32_t type) {
    PH_COVERS(LIGHT_TYPE_COUNT, 7u);
    switch (type) {
        case LIGHT_POINT: return "point";
        case LIGHT_SPOT: return "spot";
        case LIGHT_SPHERE: return "sphere";
        case LIGHT_QUAD: return "quad";
        case LIGHT_TRIANGLES: return "emissive triangles";
        case LIGHT_DIRECTIONAL: return "directional";
        case LIGHT_ENVIRONMENT: return "environment";
    }
    throw std::logic_error("unknown light type " + std::to_string(type));
}

// A directional light's handle: a point on its side of the scene, twice the bounding radius out.
glm::vec3 Scene::lightHandle(std::uint32_t light) const {
    const Light& l = lights.at(light);
    if (l.type == LIGHT_DIRECTIONAL) {
        return boundingCenter(l) - 2.0f * boundingRadius(l) * directionalDirection(l);
    }
    return l.position;
}

void Scene::moveLight(std::uint32_t light, glm::vec3 delta) {
    Light& l = lights.at(light);
    // The emitter surface that addSphereLight/addQuadLight made carries the material named after it.
    std::uint32_t emitter = findMaterial("light" + std::to_string(light));
    bool ownSurface = emitter != NONE && materials[emitter].type == MATERIAL_EMITTER;
    PH_COVERS(LIGHT_TYPE_COUNT, 7u);
    switch (l.type) {
        case LIGHT_POINT:
        case LIGHT_SPOT:
            l.position += delta;
            break;
        case LIGHT_SPHERE:
            l.position += delta;
            moveShapesOf(spheres, &Sphere::center, ownSurface ? emitter : NONE, delta);
            break;
        case LIGHT_QUAD:
            l.position += delta;
            moveShapesOf(quads, &Quad::corner, ownSurface ? emitter : NONE, delta);
            break;
        case LIGHT_TRIANGLES:
            // The triangles finalize() gathered into this light (it makes the light again).
            for (Triangle& t : triangles) {
                const Material& m = materials[t.material];
                if (m.type != MATERIAL_EMITTER && !isBlack(m.emission)) {
                    t.v0 += delta;
                    t.v1 += delta;
                    t.v2 += delta;
                }
            }
            l.position += delta;
            break;
        case LIGHT_DIRECTIONAL:
            // The light turns to shine from its moved handle towards the scene's centre.
            if (delta != glm::vec3(0.0f)) {
                l.axis = glm::normalize(boundingCenter(l) - (lightHandle(light) + delta));
            }
            break;
        case LIGHT_ENVIRONMENT:
            break;  // everywhere: nothing to move (it turns by its rotation)
    }
}

void Scene::setEnvironment(EnvironmentLight light) {
    auto start = std::chrono::steady_clock::now();
    EnvironmentDistribution d = buildEnvironmentDistribution(light.map);
    environmentBuildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    environmentTexels = std::move(d.texels);
    environmentCdf = std::move(d.cdf);
    environmentIntegral = d.integral;
    environment = std::move(light);
}

void Scene::setBackground(glm::vec3 radiance) {
    EnvironmentLight light;
    light.radiance = radiance;
    light.lights = false;
    setEnvironment(std::move(light));
}

double widestSpan(glm::vec3 lo, glm::vec3 hi) {
    return std::max({double(hi.x) - double(lo.x), double(hi.y) - double(lo.y), double(hi.z) - double(lo.z)});
}

std::string describeSpan(glm::vec3 lo, glm::vec3 hi) {
    int axis = 0;
    for (int a = 1; a < 3; ++a) {
        if (double(hi[a]) - double(lo[a]) > double(hi[axis]) - double(lo[axis])) {
            axis = a;
        }
    }
    char text[96];
    std::snprintf(text, sizeof text, "%.6g wide (%c from %.6g to %.6g)", widestSpan(lo, hi), "xyz"[axis], double(lo[axis]),
                  double(hi[axis]));
    return text;
}

float Scene::diagonal() const { return glm::length(boundsMax - boundsMin); }

Camera makeCamera(const CameraDesc& desc, std::uint32_t width, std::uint32_t height) {
    Camera c{};
    c.position = desc.position;
    c.forward = glm::normalize(desc.lookAt - desc.position);
    c.right = glm::normalize(glm::cross(c.forward, desc.up));
    c.up = glm::cross(c.right, c.forward);
    c.tanHalfFovY = static_cast<float>(std::tan(0.5 * double(desc.fovY) * 3.14159265358979323846 / 180.0));
    c.aspect = float(width) / float(height);
    c.lensRadius = desc.lensRadius;
    c.focusDistance = desc.focusDistance > 0.0f ? desc.focusDistance : glm::length(desc.lookAt - desc.position);
    return c;
}

bool Scene::makesCausticPaths() const {
    return std::any_of(materials.begin(), materials.end(), [](const Material& m) { return photon::makesCausticPaths(m); });
}

#define PH_SCENE_ARRAY_CASE(NAME, b, T, name, access, sizeClass) \
    PH_SCENE_ONLY_##sizeClass(if (binding == b) { return {scene.name.data(), scene.name.size()}; })

HostArray sceneArray(const Scene& scene, std::uint32_t binding) {
    PH_BUFFERS(PH_SCENE_ARRAY_CASE)
    return {};
}

#define PH_BIND_SCENE_ARRAY(NAME, b, T, name, access, sizeClass) PH_SCENE_ONLY_##sizeClass(bindings.name = scene.name.data();)

void bindSceneArrays(Bindings& bindings, const Scene& scene) { PH_BUFFERS(PH_BIND_SCENE_ARRAY) }

}  // namespace photon
