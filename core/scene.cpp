#include "scene.h"

#include <algorithm>
#include <cmath>

#include "shared/material.h"

namespace photon {
namespace {

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

// 1 - cos θ for θ in degrees, as 2 sin²(θ/2): exact for tiny angles.
float oneMinusCosDegrees(double degrees) {
    double s = std::sin(0.5 * degrees * 3.14159265358979323846 / 180.0);
    return static_cast<float>(2.0 * s * s);
}

void grow(glm::vec3& lo, glm::vec3& hi, glm::vec3 p, float r) {
    lo = glm::min(lo, p - glm::vec3(r));
    hi = glm::max(hi, p + glm::vec3(r));
}

}  // namespace

Material makeDiffuse(glm::vec3 albedo) {
    Material m{};
    m.type = MATERIAL_DIFFUSE;
    m.albedo = albedo;
    m.ior = 1.0f;
    return m;
}

Material makeMirror(glm::vec3 reflectance) {
    Material m{};
    m.type = MATERIAL_MIRROR;
    m.specular = reflectance;
    m.ior = 1.0f;
    return m;
}

Material makeGlass(float ior, glm::vec3 tint) {
    Material m{};
    m.type = MATERIAL_GLASS;
    m.specular = tint;
    m.ior = ior;
    return m;
}

Material makeGlossy(glm::vec3 albedo, glm::vec3 specular, float roughness) {
    Material m{};
    m.type = MATERIAL_GLOSSY;
    m.albedo = albedo;
    m.specular = specular;
    m.roughness = roughness;
    m.ior = 1.0f;
    return m;
}

Material makeReflective(glm::vec3 albedo, glm::vec3 reflectance) {
    Material m{};
    m.type = MATERIAL_REFLECTIVE;
    m.albedo = albedo;
    m.specular = reflectance;
    m.ior = 1.0f;
    return m;
}

Material makeEmitter(glm::vec3 radiance) {
    Material m{};
    m.type = MATERIAL_EMITTER;
    m.emission = radiance;
    m.ior = 1.0f;
    return m;
}

std::uint32_t Scene::addMaterial(const std::string& materialName, const Material& m) {
    materials.push_back(m);
    materialNames.push_back(materialName);
    return static_cast<std::uint32_t>(materials.size() - 1);
}

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
    t.edge1 = b - a;
    t.edge2 = c - a;
    t.material = material;
    triangles.push_back(t);
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
    l.radius = radius;
    l.area = 4.0f * PI * radius * radius;
    lights.push_back(l);
    std::uint32_t m = addMaterial("light" + std::to_string(lights.size() - 1), makeEmitter(power * (INV_PI / l.area)));
    addSphere(center, radius, m);
}

void Scene::addQuadLight(glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, glm::vec3 power) {
    Light l = emptyLight(LIGHT_QUAD, corner, power);
    l.edgeU = edgeU;
    l.edgeV = edgeV;
    glm::vec3 n = glm::cross(edgeU, edgeV);
    l.area = glm::length(n);
    l.axis = n / l.area;
    lights.push_back(l);
    std::uint32_t m = addMaterial("light" + std::to_string(lights.size() - 1), makeEmitter(power * (INV_PI / l.area)));
    addQuad(corner, edgeU, edgeV, m);
}

void Scene::finalize() {
    // Lights are picked in proportion to their mean power.
    // Sums in double: powers near the float limit must not overflow into 0 or NaN probabilities.
    auto meanPower = [](const Light& l) { return (double(l.power.x) + double(l.power.y) + double(l.power.z)) / 3.0; };
    double total = 0.0;
    for (const Light& l : lights) {
        total += meanPower(l);
    }
    double cdf = 0.0;
    for (Light& l : lights) {
        double p = total > 0.0 ? meanPower(l) / total : 1.0 / double(lights.size());
        l.pickProbability = static_cast<float>(p);
        cdf += p;
        l.pickCdf = static_cast<float>(cdf);
    }
    if (!lights.empty()) {
        lights.back().pickCdf = 1.0f;
    }

    auto specular = [&](std::uint32_t m) { return surfaceIs(materials[m], SURFACE_CAUSTIC_CASTER); };
    targets.clear();
    glm::vec3 lo(FLOAT_MAX);
    glm::vec3 hi(-FLOAT_MAX);
    for (const Sphere& s : spheres) {
        grow(lo, hi, s.center, s.radius);
        if (specular(s.material)) {
            targets.push_back({s.center, s.radius});
        }
    }
    for (const Quad& q : quads) {
        glm::vec3 c = q.corner + 0.5f * (q.edgeU + q.edgeV);
        float r = 0.5f * std::max(glm::length(q.edgeU + q.edgeV), glm::length(q.edgeU - q.edgeV));
        grow(lo, hi, c, r);
        if (specular(q.material)) {
            targets.push_back({c, r});
        }
    }
    for (const Triangle& t : triangles) {
        glm::vec3 c = t.v0 + (t.edge1 + t.edge2) / 3.0f;
        float r = std::max({glm::length(t.v0 - c), glm::length(t.v0 + t.edge1 - c), glm::length(t.v0 + t.edge2 - c)});
        grow(lo, hi, c, r);
        if (specular(t.material)) {
            targets.push_back({c, r});
        }
    }
    for (const Light& l : lights) {
        grow(lo, hi, l.position, l.radius);
    }
    if (lo.x > hi.x) {
        lo = glm::vec3(-1.0f);
        hi = glm::vec3(1.0f);
    }
    boundsMin = lo;
    boundsMax = hi;
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
