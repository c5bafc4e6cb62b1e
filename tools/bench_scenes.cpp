#include "bench_scenes.h"

#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/loaders/scene_loader.h"
#include "mesh_shapes.h"

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

}  // namespace photon::tools
