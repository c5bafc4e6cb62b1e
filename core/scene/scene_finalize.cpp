// Scene::finalize, job by job: check what the shared code will read unchecked, flag the
// triangles rays must test or cull, bound the scene, size the lights that depend on the bounds,
// gather the emissive triangles into one light, give every light its pick probability, set up
// the infinite light, aim the caustic pass, and build the BVH.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "shared/light_types.h"
#include "shared/material.h"

namespace photon {
namespace {

void grow(glm::vec3& lo, glm::vec3& hi, glm::vec3 p, float r) {
    lo = glm::min(lo, p - glm::vec3(r));
    hi = glm::max(hi, p + glm::vec3(r));
}

// The sphere bounding targets [first, last).
CausticTarget boundingTarget(const std::vector<CausticTarget>& t, std::size_t first, std::size_t last) {
    glm::vec3 lo(FLOAT_MAX);
    glm::vec3 hi(-FLOAT_MAX);
    for (std::size_t i = first; i < last; ++i) {
        lo = glm::min(lo, t[i].center - glm::vec3(t[i].radius));
        hi = glm::max(hi, t[i].center + glm::vec3(t[i].radius));
    }
    CausticTarget b{0.5f * (lo + hi), 0.0f};
    for (std::size_t i = first; i < last; ++i) {
        b.radius = std::max(b.radius, glm::length(t[i].center - b.center) + t[i].radius);
    }
    return b;
}

// At most `limit` targets: groups split at the median of their centres along their longest
// extent, the largest group first, each group then one bounding sphere. The caustic pass aims at
// fewer, larger cones, and stays unbiased.
void mergeTargets(std::vector<CausticTarget>& targets, std::size_t limit) {
    if (targets.size() <= limit) {
        return;
    }
    std::vector<std::pair<std::size_t, std::size_t>> groups{{0, targets.size()}};
    while (groups.size() < limit) {
        std::size_t widest = groups.size();
        float widestRadius = -1.0f;
        for (std::size_t g = 0; g < groups.size(); ++g) {
            float r = boundingTarget(targets, groups[g].first, groups[g].second).radius;
            if (groups[g].second - groups[g].first > 1 && r > widestRadius) {
                widest = g;
                widestRadius = r;
            }
        }
        if (widest == groups.size()) {
            break;
        }
        auto [first, last] = groups[widest];
        glm::vec3 lo(FLOAT_MAX);
        glm::vec3 hi(-FLOAT_MAX);
        for (std::size_t i = first; i < last; ++i) {
            lo = glm::min(lo, targets[i].center);
            hi = glm::max(hi, targets[i].center);
        }
        glm::vec3 e = hi - lo;
        int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
        std::size_t middle = first + (last - first) / 2;
        std::nth_element(targets.begin() + std::ptrdiff_t(first), targets.begin() + std::ptrdiff_t(middle),
                         targets.begin() + std::ptrdiff_t(last),
                         [axis](const CausticTarget& x, const CausticTarget& y) { return x.center[axis] < y.center[axis]; });
        groups[widest] = {first, middle};
        groups.push_back({middle, last});
    }
    std::vector<CausticTarget> merged;
    for (auto [first, last] : groups) {
        merged.push_back(boundingTarget(targets, first, last));
    }
    targets = merged;
}

// Every material, texture reference and light the shared code will read unchecked is valid.
void checkReferences(const Scene& scene) {
    // Every material is of a known type and every texture it names exists: the shared code
    // samples them unchecked.
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        if (m.type >= MATERIAL_TYPE_COUNT) {
            throw std::logic_error("material " + scene.materialNames[i] + " has unknown type " + std::to_string(m.type));
        }
        for (std::uint32_t texture : {m.albedoTexture, m.metallicRoughnessTexture, m.normalTexture, m.emissionTexture}) {
            if (texture != NONE && texture >= scene.textures.size()) {
                throw std::logic_error("material " + scene.materialNames[i] + " names texture " + std::to_string(texture) +
                                       " of " + std::to_string(scene.textures.size()));
            }
        }
    }
    // Every light is of a type the shared code knows: its switches have a case for each type and
    // nothing for any other. The infinite one is the scene's environment, which finalize adds.
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        std::uint32_t type = scene.lights[i].type;
        if (type >= LIGHT_TYPE_COUNT) {
            throw std::logic_error("light " + std::to_string(i) + " has unknown type " + std::to_string(type));
        }
        if ((lightFlags(type) & LIGHT_FLAG_INFINITE) != 0u && i != scene.environmentLight) {
            throw std::logic_error("light " + std::to_string(i) + " is an infinite light: a scene has one, its environment");
        }
    }
    const EnvironmentMap& map = scene.environment.map;
    if (scene.environmentTexels.size() != std::size_t(map.width) * map.height ||
        (map.height > 0 && scene.environmentCdf.size() != (map.height + 1) + std::size_t(map.height) * (map.width + 1))) {
        throw std::logic_error("the environment's map changed without setEnvironment()");
    }
}

void flagTriangles(Scene& scene) {
    // Triangles whose material cuts them out or blends them are tested for coverage by every ray;
    // single-sided opaque ones have no back. (A transmissive surface keeps both sides whatever the
    // file says: light that entered a glass body must be able to leave it.)
    for (Triangle& t : scene.triangles) {
        const Material& m = scene.materials[t.material];
        bool tested = (m.flags & (MATERIAL_FLAG_ALPHA_MASK | MATERIAL_FLAG_ALPHA_BLEND)) != 0u;
        bool culled = (m.flags & MATERIAL_FLAG_SINGLE_SIDED) != 0u && !(m.type == MATERIAL_PBR && m.transmission > 0.0f) &&
                      m.type != MATERIAL_GLASS;
        t.flags = (tested ? TRIANGLE_ALPHA_TESTED : 0u) | (culled ? TRIANGLE_BACK_CULLED : 0u);
    }
}

void computeBounds(Scene& scene) {
    // Bounds of everything finite (lights' own positions included).
    glm::vec3 lo(FLOAT_MAX);
    glm::vec3 hi(-FLOAT_MAX);
    for (const Sphere& s : scene.spheres) {
        grow(lo, hi, s.center, s.radius);
    }
    for (const Quad& q : scene.quads) {
        for (glm::vec3 p : {q.corner, q.corner + q.edgeU, q.corner + q.edgeV, q.corner + q.edgeU + q.edgeV}) {
            grow(lo, hi, p, 0.0f);
        }
    }
    for (const Triangle& t : scene.triangles) {
        lo = glm::min(lo, glm::min(t.v0, glm::min(t.v1, t.v2)));
        hi = glm::max(hi, glm::max(t.v0, glm::max(t.v1, t.v2)));
    }
    // A medium's box (a grid's, or one the scene file gave) holds light that the camera sees.
    for (const Medium& md : scene.media) {
        if (md.lower.x > -kMediumUnbounded) {
            lo = glm::min(lo, md.lower);
            hi = glm::max(hi, md.upper);
        }
    }
    for (const Light& l : scene.lights) {
        PH_COVERS(LIGHT_TYPE_COUNT, 7u);
        switch (l.type) {
            case LIGHT_POINT:
            case LIGHT_SPOT:
                grow(lo, hi, pointPosition(l), 0.0f);
                break;
            case LIGHT_SPHERE:
                grow(lo, hi, sphereCenter(l), sphereRadius(l));
                break;
            case LIGHT_QUAD:
                grow(lo, hi, quadCorner(l), 0.0f);  // its surface, a quad, is in the bounds already
                break;
            case LIGHT_TRIANGLES:    // its scene.triangles are
            case LIGHT_DIRECTIONAL:  // at infinity, and sized to the bounds below
            case LIGHT_ENVIRONMENT:  // likewise
                break;
        }
    }
    if (lo.x > hi.x) {
        lo = glm::vec3(-1.0f);
        hi = glm::vec3(1.0f);
    }
    scene.boundsMin = lo;
    scene.boundsMax = hi;
}

// The scene's medium fills its bounds unless it was given a box; a box that misses the scene is
// the scene file's mistake, which a render would show as no medium at all.
void boundSceneMedium(Scene& scene) {
    if (scene.medium == NONE) {
        return;
    }
    Medium& md = scene.media[scene.medium];
    if (md.lower.x <= -kMediumUnbounded) {
        glm::vec3 margin = 1e-3f * (scene.boundsMax - scene.boundsMin) + glm::vec3(1e-6f);
        md.lower = scene.boundsMin - margin;
        md.upper = scene.boundsMax + margin;
    }
}

void sizeDirectionalLights(Scene& scene) {
    glm::vec3 lo = scene.boundsMin;
    glm::vec3 hi = scene.boundsMax;
    // Directional lights cover the sphere around the bounds.
    glm::vec3 centre = 0.5f * (lo + hi);
    float radius = std::max(0.5f * glm::length(hi - lo), 1e-6f);
    for (Light& l : scene.lights) {
        if (l.type == LIGHT_DIRECTIONAL) {
            l.position = centre;  // boundingCenter
            l.extent = radius;    // boundingRadius
            l.power = directionalIrradiance(l) * (PI * radius * radius);
        }
    }
}

void gatherEmissiveTriangles(Scene& scene) {
    glm::vec3 centre = 0.5f * (scene.boundsMin + scene.boundsMax);
    // One light for every emissive triangle, which picks them by power (πL·area, mean over
    // channels; sums in double).
    std::vector<Light>& lights = scene.lights;
    lights.erase(std::remove_if(lights.begin(), lights.end(), [](const Light& l) { return l.type == LIGHT_TRIANGLES; }),
                 lights.end());
    scene.emissiveTriangles.clear();
    glm::dvec3 flux(0.0);
    std::vector<double> powers;
    for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
        const Triangle& t = scene.triangles[i];
        glm::vec3 emission = scene.materials[t.material].emission;
        if (scene.materials[t.material].type == MATERIAL_EMITTER || isBlack(emission)) {
            continue;
        }
        float area = 0.5f * glm::length(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
        glm::dvec3 p = glm::dvec3(emission) * (double(PI) * double(area));
        scene.emissiveTriangles.push_back({std::uint32_t(i), 0.0f, 0.0f, area});
        powers.push_back((p.x + p.y + p.z) / 3.0);
        flux += p;
    }
    if (!scene.emissiveTriangles.empty()) {
        double total = 0.0;
        for (double p : powers) {
            total += p;
        }
        double cdf = 0.0;
        for (std::size_t i = 0; i < scene.emissiveTriangles.size(); ++i) {
            double p = total > 0.0 ? powers[i] / total : 1.0 / double(powers.size());
            cdf += p;
            scene.emissiveTriangles[i].probability = static_cast<float>(p);
            scene.emissiveTriangles[i].cdf = static_cast<float>(cdf);
        }
        scene.emissiveTriangles.back().cdf = 1.0f;
        Light l = emptyLight(LIGHT_TRIANGLES, centre, glm::vec3(flux));
        l.emitterFirst = 0;
        l.emitterCount = std::uint32_t(scene.emissiveTriangles.size());
        scene.lights.push_back(l);
    }
}

void assignPickProbabilities(Scene& scene) {
    // Lights are picked in proportion to their mean power.
    // Sums in double: powers near the float limit must not overflow into 0 or NaN probabilities.
    auto meanPower = [](const Light& l) { return (double(l.power.x) + double(l.power.y) + double(l.power.z)) / 3.0; };
    double total = 0.0;
    for (const Light& l : scene.lights) {
        total += meanPower(l);
    }
    double cdf = 0.0;
    for (Light& l : scene.lights) {
        double p = total > 0.0 ? meanPower(l) / total : 1.0 / double(scene.lights.size());
        l.pickProbability = static_cast<float>(p);
        cdf += p;
        l.pickCdf = static_cast<float>(cdf);
    }
    if (!scene.lights.empty()) {
        scene.lights.back().pickCdf = 1.0f;
    }
}

// What rays that leave the scene see: its environment, in `infiniteLights`; and if it lights the
// scene, a copy in `lights` (the last), sized like a directional light to the bounding sphere.
void placeEnvironment(Scene& scene) {
    std::vector<Light>& lights = scene.lights;
    lights.erase(std::remove_if(lights.begin(), lights.end(), [](const Light& l) { return l.type == LIGHT_ENVIRONMENT; }),
                 lights.end());
    scene.environmentLight = NONE;
    const EnvironmentLight& env = scene.environment;
    glm::vec3 centre = 0.5f * (scene.boundsMin + scene.boundsMax);
    float radius = std::max(0.5f * glm::length(scene.boundsMax - scene.boundsMin), 1e-6f);
    Light l = emptyLight(LIGHT_ENVIRONMENT, centre, glm::vec3(0.0f));
    l.extent = radius;  // boundingRadius
    glm::vec3 half = 0.5f * (scene.boundsMax - scene.boundsMin);  // boundsHalfExtent
    l.area = half.x;
    l.spanY = half.y;
    l.spanZ = half.z;
    l.vectorU = env.radiance;  // environmentScale
    l.emitterFirst = env.map.width;
    l.emitterCount = env.map.height;
    l.vectorV = glm::normalize(env.rotation[0]);  // environmentMapX
    l.axis = glm::normalize(env.rotation[1]);     // environmentMapY
    // Its power for picking lights: πR² ∫ L dω, the flux through the bounding sphere's disks (an
    // upper bound of the flux into the bounding box, where its photons start; any pick weights
    // keep the estimate unbiased).
    glm::dvec3 integral = env.map.empty() ? glm::dvec3(4.0 * double(PI)) : scene.environmentIntegral;
    l.power = glm::vec3(glm::dvec3(env.radiance) * integral * (double(PI) * double(radius) * double(radius)));
    scene.infiniteLights = {l};
    if (env.lights && !isBlack(l.power)) {
        scene.environmentLight = std::uint32_t(lights.size());
        lights.push_back(l);
    }
}

void placeCausticTargets(Scene& scene) {
    // Caustic targets: a bounding sphere for each bounded caster, a mesh's casters as one.
    auto caster = [&](std::uint32_t m) { return surfaceIs(scene.materials[m], SURFACE_CAUSTIC_CASTER); };
    scene.targets.clear();
    for (const Sphere& s : scene.spheres) {
        if (caster(s.material)) {
            scene.targets.push_back({s.center, s.radius});
        }
    }
    for (const Quad& q : scene.quads) {
        if (caster(q.material)) {
            glm::vec3 c = q.corner + 0.5f * (q.edgeU + q.edgeV);
            float r = 0.5f * std::max(glm::length(q.edgeU + q.edgeV), glm::length(q.edgeU - q.edgeV));
            scene.targets.push_back({c, r});
        }
    }
    for (const TriangleObject& object : scene.objects) {
        glm::vec3 tlo(FLOAT_MAX);
        glm::vec3 thi(-FLOAT_MAX);
        for (std::uint32_t i = object.first; i < object.first + object.count; ++i) {
            const Triangle& t = scene.triangles[i];
            if (caster(t.material)) {
                tlo = glm::min(tlo, glm::min(t.v0, glm::min(t.v1, t.v2)));
                thi = glm::max(thi, glm::max(t.v0, glm::max(t.v1, t.v2)));
            }
        }
        if (tlo.x <= thi.x) {
            glm::vec3 c = 0.5f * (tlo + thi);
            float r = 0.0f;
            for (std::uint32_t i = object.first; i < object.first + object.count; ++i) {
                const Triangle& t = scene.triangles[i];
                if (caster(t.material)) {
                    r = std::max({r, glm::length(t.v0 - c), glm::length(t.v1 - c), glm::length(t.v2 - c)});
                }
            }
            scene.targets.push_back({c, r * (1.0f + 1e-5f)});
        }
    }
    mergeTargets(scene.targets, CAUSTIC_TARGETS_MAX);
}

}  // namespace

void Scene::finalize() {
    checkReferences(*this);
    flagTriangles(*this);
    computeBounds(*this);
    boundSceneMedium(*this);
    sizeDirectionalLights(*this);
    gatherEmissiveTriangles(*this);
    placeEnvironment(*this);
    assignPickProbabilities(*this);
    placeCausticTargets(*this);
    bvh = buildBvh(*this, bvhNodes, primitiveRefs);
}

}  // namespace photon
