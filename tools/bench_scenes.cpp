#include "bench_scenes.h"

#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/loaders/scene_loader.h"
#include "core/system/input_file.h"
#include "mesh_shapes.h"
#include "smoke_field.h"

namespace photon::tools {

Scene meshBenchScene(std::uint64_t triangles, bool glass) {
    Scene scene = defaultScene();
    scene.spheres.clear();
    Mesh mesh = bumpySphere(triangles);
    std::uint32_t material = glass ? scene.addMaterial("bench glass", makeGlass(1.5f, glm::vec3(1.0f)))
                                   : scene.addMaterial("bench white", makeDiffuse(glm::vec3(0.75f)));
    mesh.materials.assign(mesh.triangles.size(), material);
    // Radius 0.55 (the bumps reach about 10% further) standing on the floor of the 2 × 2 × 2 box.
    glm::mat4 transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.62f, 0.0f)) *
                          glm::scale(glm::mat4(1.0f), glm::vec3(0.55f));
    scene.addMesh(mesh, transform);
    scene.name = "mesh-" + std::to_string(scene.triangles.size());
    scene.finalize();
    return scene;
}

Scene smokeBenchScene(const std::string& scenesDir, std::uint32_t resolution) {
    // smoke.json with its grid's file left out: the same medium, the plume put in its place.
    std::string text = readInputFile(scenesDir + "/smoke.json", kSceneFileLimit, "scene file");
    nlohmann::json document = nlohmann::json::parse(text);
    nlohmann::json& grid = document["media"]["smoke"]["grid"];
    glm::vec3 lower(grid["min"][0], grid["min"][1], grid["min"][2]);
    glm::vec3 upper(grid["max"][0], grid["max"][1], grid["max"][2]);
    document["media"]["smoke"].erase("grid");
    Scene scene = loadSceneJson(document.dump(), scenesDir + "/smoke.json (its grid made by code)");
    DensityGrid plume = makeSmokePlume(glm::uvec3(resolution, 2 * resolution, resolution), 1u);
    plume.lower = lower;
    plume.upper = upper;
    Medium& md = scene.media[scene.medium];
    md.grid = scene.addDensityGrid(plume);
    md.resolution = plume.resolution;
    md.lower = lower;
    md.upper = upper;
    scene.name = "smoke-" + std::to_string(resolution);
    scene.finalize();
    return scene;
}

}  // namespace photon::tools
