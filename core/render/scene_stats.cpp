#include "core/render/scene_stats.h"

#include "shared/bindings.h"

namespace photon {

nlohmann::json sceneStatsJson(const Scene& scene) {
    nlohmann::json j;
    j["spheres"] = scene.spheres.size();
    j["planes"] = scene.planes.size();
    j["quads"] = scene.quads.size();
    j["triangles"] = scene.triangles.size();
    j["dropped_triangles"] = scene.droppedTriangles;
    j["emissive_triangles"] = scene.emissiveTriangles.size();
    j["textures"] = scene.textures.size();
    j["texels"] = scene.texels.size();
    j["lights"] = scene.lights.size();
    j["caustic_targets"] = scene.targets.size();
    // Of everything finite (Scene::finalize): what a tool needs to frame the scene.
    j["bounds"] = {{"min", {scene.boundsMin.x, scene.boundsMin.y, scene.boundsMin.z}},
                   {"max", {scene.boundsMax.x, scene.boundsMax.y, scene.boundsMax.z}}};
    j["bvh"] = {{"primitives", scene.bvh.primitives},
                {"nodes", scene.bvh.nodes},
                {"leaves", scene.bvh.leaves},
                {"depth", scene.bvh.depth},
                {"sah_cost", scene.bvh.sahCost},
                {"wide_nodes", scene.bvh.wideNodes},
                {"wide_depth", scene.bvh.wideDepth},
                {"wide_sah_cost", scene.bvh.wideSahCost},
                {"stack", scene.bvh.stack},
                {"build_seconds", scene.bvh.buildSeconds}};
    j["environment"] = {{"source", scene.environment.source.empty() ? "uniform" : scene.environment.source},
                        {"width", scene.environment.map.width},
                        {"height", scene.environment.map.height},
                        {"lights", scene.environmentLight != NONE},
                        {"distribution_build_seconds", scene.environmentBuildSeconds}};
    std::uint64_t total = 0;
    nlohmann::json buffers = nlohmann::json::object();
    for (const BufferInfo& info : kBuffers) {
        if (info.size == BUFFER_PER_SCENE) {
            std::uint64_t bytes = std::uint64_t(sceneArray(scene, info.binding).count) * info.elementBytes;
            buffers[info.name] = bytes;
            total += bytes;
        }
    }
    j["buffer_bytes"] = buffers;
    j["total_bytes"] = total;
    // A triangle's share: itself, its attributes, and the hierarchy's nodes and references over
    // all bounded primitives (its part of them).
    if (!scene.triangles.empty()) {
        double bounded = double(scene.spheres.size() + scene.quads.size() + scene.triangles.size());
        double hierarchy = double(scene.bvhNodes.size() * sizeof(WideBvhNode) + scene.primitiveRefs.size() * sizeof(std::uint32_t));
        double own = double(scene.triangles.size() * sizeof(Triangle) + scene.triangleAttributes.size() * sizeof(TriangleAttributes));
        j["bytes_per_triangle"] = own / double(scene.triangles.size()) + hierarchy / bounded;
    }
    j["bytes_per_texel"] = sizeof(glm::uvec2);
    return j;
}

}  // namespace photon
