// A heterogeneous medium's density on the host: a dense grid of voxels, each of constant density,
// tiling a box in scene units. Read from OpenVDB files (core/loaders/vdb_loader.h) or made by
// code (tools/smoke_field.h); a Medium scales its coefficients by it (shared/medium_grid.h).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace photon {

struct DensityGrid {
    glm::uvec3 resolution{0u};   // voxels along x, y, z
    glm::vec3 lower{0.0f};       // the box the voxels tile [scene units]
    glm::vec3 upper{0.0f};
    std::vector<float> density;  // resolution.x · y · z voxels, x fastest, then y, then z; finite, ≥ 0

    float at(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
        return density[x + resolution.x * (y + std::size_t(resolution.y) * z)];
    }
};

// The most voxels along one axis of a grid that a scene may hold (a file's grid is averaged down
// to it), and the most voxels of all the scene's grids together.
inline constexpr std::uint32_t kDensityResolutionMax = 512;
inline constexpr std::uint64_t kDensityVoxelsMax = std::uint64_t(1) << 28;

}  // namespace photon
