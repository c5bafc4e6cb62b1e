// What a scene costs, for --stats and photon-bench: its primitives (and the triangles its meshes
// dropped), the BVH over them, and the bytes of every scene buffer, per triangle and per texel.
#pragma once

#include <nlohmann/json.hpp>

#include "core/scene/scene.h"

namespace photon {

nlohmann::json sceneStatsJson(const Scene& scene);

}  // namespace photon
