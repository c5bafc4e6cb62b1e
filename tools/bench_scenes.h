// Scenes of any size for photon-bench and the tests: the Cornell box with its spheres replaced by
// a bumpy sphere of about `triangles` triangles (tools/mesh_shapes.h), so that cost can be
// measured as a function of the triangle count with everything else the same.
#pragma once

#include <cstdint>
#include <string>

#include "core/scene/scene.h"

namespace photon::tools {

// `glass`: the mesh is glass (a caustic caster) instead of white diffuse.
Scene meshBenchScene(std::uint64_t triangles, bool glass = false);

// scenes/smoke.json without its file: the smoke plume made by code (tools/smoke_field.h) at
// `resolution` voxels across (twice as many high), so that builds without OpenVDB (the GPU
// machine's) measure heterogeneous media, and cost can be measured against the voxel count.
Scene smokeBenchScene(const std::string& scenesDir, std::uint32_t resolution);

}  // namespace photon::tools
