// Heterogeneous media for the tests: a density grid from a hash, and the fog-filled Cornell box
// (scenes/fog.json) with its fog made heterogeneous by one.
#pragma once

#include <string>

#include "core/loaders/scene_loader.h"
#include "core/scene/scene.h"
#include "test_util.h"

namespace photon::test {

// n voxels along each axis over [lower, upper], densities in [0, 2) from a hash; a quarter of the
// voxels are empty, so that walks cross holes.
inline DensityGrid hashedDensityGrid(glm::uvec3 n, glm::vec3 lower, glm::vec3 upper) {
    DensityGrid g;
    g.resolution = n;
    g.lower = lower;
    g.upper = upper;
    for (std::uint32_t i = 0; i < n.x * n.y * n.z; ++i) {
        std::uint32_t h = i * 2654435761u;
        h ^= h >> 15;
        h *= 2246822519u;
        h ^= h >> 13;
        float u = float(h & 0xFFFFu) / 65536.0f;
        g.density.push_back(u < 0.25f ? 0.0f : 2.0f * u);
    }
    return g;
}

// Medium `index` of the scene made heterogeneous by a hashed grid of n³ voxels over its box.
inline void makeHeterogeneous(Scene& scene, std::uint32_t index, std::uint32_t n) {
    Medium& md = scene.media[index];
    DensityGrid grid = hashedDensityGrid(glm::uvec3(n), md.lower, md.upper);
    md.grid = scene.addDensityGrid(grid);
    md.resolution = grid.resolution;
}

inline Scene heterogeneousFog() {
    Scene scene = loadSceneFile(scenesDir() + "/fog.json");
    makeHeterogeneous(scene, scene.medium, 12);
    scene.name = "fog.json, heterogeneous";
    return scene;
}

}  // namespace photon::test
