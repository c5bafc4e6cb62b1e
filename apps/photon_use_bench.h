// photon-bench --photon-use: how many of a frame's stored photons any pixel gathers, per scene and
// map (issue 20: photons where they count).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/frame/renderer.h"

namespace photon {

struct PhotonUseCase {
    std::string scene;
    RenderSettings settings;
};

// Renders each case `frames` frames on `backend` and prints, per map, the last frame's stored
// photons, the share of them within some pixel's disc (core/frame/photon_use.h) and the pixels
// that gather from it.
void benchPhotonUse(Renderer& backend, const std::vector<std::pair<Scene, PhotonUseCase>>& cases, std::uint32_t frames);

}  // namespace photon
