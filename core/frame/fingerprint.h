// What the processes of an MPI render must share, hashed item by item so that the first process
// can name what another holds differently: the scene's arrays (a stale copy of a file on one
// host), the camera, and each render setting (a different seed, estimator or photon count would
// give a silently different image, and a different frame count a hang).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "core/settings/settings.h"

namespace photon {

struct Fingerprint {
    std::string name;  // for messages: "the scene's triangles", "the camera", "--photons"
    std::uint64_t hash = 0;
};

// The scene's arrays (PH_BUFFERS' scene buffers) one item each, the camera, then every setting of
// the settings table by its flag.
std::vector<Fingerprint> renderFingerprints(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings);

}  // namespace photon
