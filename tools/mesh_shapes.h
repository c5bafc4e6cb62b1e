// Meshes made by code, for tests and benchmarks: tessellated spheres with smooth normals, and
// bumpy spheres and terrains of any number of triangles.
#pragma once

#include <cstdint>

#include "core/scene/mesh.h"

namespace photon::tools {

// A UV sphere of `stacks` × `slices` quads (2·stacks·(slices - 1) triangles), outward, vertex
// normals exact (the sphere's own) when `smooth`, else none. Material 0.
Mesh uvSphere(glm::vec3 centre, float radius, std::uint32_t stacks, std::uint32_t slices, bool smooth);

// About `triangles` triangles of a sphere of radius 1 whose surface is bumped by a sum of waves,
// with smooth normals: an organic shape whose BVH is a fair test (what scanned models are like).
Mesh bumpySphere(std::uint64_t triangles);

// About `triangles` triangles of a height field over [-1, 1]², with smooth normals.
Mesh terrain(std::uint64_t triangles);

}  // namespace photon::tools
