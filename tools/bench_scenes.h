// Scenes of any size for photon-bench and the tests: the Cornell box with its spheres replaced by
// a bumpy sphere of about `triangles` triangles (tools/mesh_shapes.h), so that cost can be
// measured as a function of the triangle count with everything else the same.
#pragma once

#include <cstdint>

#include "core/scene/scene.h"

namespace photon::tools {

// `glass`: the mesh is glass (a caustic caster) instead of white diffuse.
Scene meshBenchScene(std::uint64_t triangles, bool glass = false);

}  // namespace photon::tools
