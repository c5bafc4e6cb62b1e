// Which of a frame's stored photons any pixel gathers: the measure behind photons guided to what
// the camera sees (Hachisuka & Jensen 2011), where a photon that no pixel's disc holds is work
// spent on nothing.
#pragma once

#include <cstdint>

#include "core/frame/renderer.h"

namespace photon {

struct PhotonUse {
    std::uint64_t stored[MAP_COUNT] = {};    // the last frame's photons of each map
    std::uint64_t gathered[MAP_COUNT] = {};  // of them, those within some pixel's disc
    std::uint64_t discs[MAP_COUNT] = {};     // the pixels whose visible point gathers from the map
};

// After a frame on `backend`: for each map, its stored photons that lie within a pixel's disc of
// estimation (estimate.h: within the radius of its visible point, within DISC_THICKNESS radii of
// its tangent plane, arriving from the front). The radii are the pixels' own under sppm (as the
// frame left them, after its update) and the frame's query radius otherwise (knn's maximum); the
// cell estimate counts the photons of the cells that hold a visible point.
PhotonUse measurePhotonUse(Renderer& backend);

}  // namespace photon
