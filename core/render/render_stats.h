// What a renderer knows at the end of a render, as photon-render's --stats file and the Python
// module's Renderer.stats() report it: the backend and device, the scene's costs, each map's
// photons and grid, the environment's aim. The stage times, wall time and warnings of a whole
// render are the caller's to add.
#pragma once

#include <nlohmann/json.hpp>

#include "core/frame/renderer.h"

namespace photon {

nlohmann::json renderStatsJson(Renderer& renderer);

}  // namespace photon
