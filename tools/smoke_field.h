// A procedural smoke plume for tests and benchmarks of heterogeneous media, made without OpenVDB
// (photon-make-smoke-vdb writes it as a .vdb file). A column rises from a small source, widens and
// thins as it goes, and is curled and torn into wisps and holes by smooth 3D value noise.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "core/scene/density_grid.h"

namespace photon::tools {

// The plume's box, in scene units (y up): 1 wide and deep, 2 tall, standing on y = 0.
inline constexpr glm::vec3 kSmokeLower{-0.5f, 0.0f, -0.5f};
inline constexpr glm::vec3 kSmokeUpper{0.5f, 2.0f, 0.5f};

// Smooth value noise in [0, 1]: a hashed value at each integer lattice point, blended by Perlin's
// quintic fade. Deterministic for a given point and seed.
float valueNoise(glm::vec3 p, std::uint32_t seed);

// Fractal sum of `octaves` octaves of valueNoise (frequency ×2, amplitude ×½ each), in [-1, 1].
float fractalNoise(glm::vec3 p, std::uint32_t seed, int octaves);

// The plume's density at a point of its box: in [0, 1], 0 near every face of the box.
float smokeDensity(glm::vec3 p, std::uint32_t seed);

// The plume sampled at the voxel centres of a grid of `resolution` voxels tiling the box.
DensityGrid makeSmokePlume(glm::uvec3 resolution, std::uint32_t seed);

}  // namespace photon::tools
