// photon-converge --camera-path: the error of what a viewer shows while its camera moves. The
// camera follows the path a frame at a time (as photon-view's scripted runs: 1/60 s a frame); at
// sample frames the images are compared with references rendered at that frame's camera. Two runs
// over the same frames: one restarting the image at every move (photon-view before reprojection:
// each frame alone), one carrying the history (shared/reproject.h); each raw and denoised.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "core/frame/renderer.h"
#include "core/scene/camera_path.h"

namespace photon {

struct OrbitMeasurement {
    CameraPath path;
    std::uint32_t frames = 120;           // frames along the path
    std::uint32_t samples = 8;            // frames compared with a reference, evenly spread
    std::uint32_t referenceFrames = 256;  // frames of each reference (its own backend, still camera)
    std::string imagesDir;                // if set: each sample's images as PFM there
};

// Renders on backends from `makeBackend`, prints a row per sample frame and the medians, and
// returns them as JSON. `settings` are the moving run's (denoise and reproject as given).
nlohmann::json measureOrbit(const std::function<std::unique_ptr<Renderer>()>& makeBackend, const Scene& scene,
                            const RenderSettings& settings, const OrbitMeasurement& m);

}  // namespace photon
