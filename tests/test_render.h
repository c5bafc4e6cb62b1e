// Rendering in the tests: settings for a small image, and a backend run for a number of frames
// (the steps that nearly every render test takes before it looks at the result).
#pragma once

#include <cstdint>

#include "core/render/devices.h"
#include "core/scene/camera_path.h"

namespace photon::test {

// `base` (a scene's own settings, or the defaults) at width × height, with `photons` photon paths
// a frame.
inline RenderSettings sizedSettings(RenderSettings base, std::uint32_t width, std::uint32_t height, std::uint32_t photons) {
    base.width = width;
    base.height = height;
    base.photons = photons;
    return base;
}

// `frames` frames of the scene on `backend`, counted from its first: setting the scene and the
// settings restarts the frames and the accumulation.
inline void renderFrames(Renderer& backend, const Scene& scene, const RenderSettings& settings, std::uint32_t frames) {
    backend.setScene(scene);
    backend.setSettings(settings);
    for (std::uint32_t f = 0; f < frames; ++f) {
        backend.renderFrame();
    }
}

// `moves` frames more on `backend`, the camera a step further along `path` from `start` before
// each: frame f is f/60 s along the path.
inline void renderAlongPath(Renderer& backend, const CameraPath& path, const CameraDesc& start, std::uint32_t moves) {
    for (std::uint32_t f = 1; f <= moves; ++f) {
        backend.moveCamera(cameraAt(path, start, f / 60.0));
        backend.renderFrame();
    }
}

// The CPU reference's accumulated image after `frames` frames of the scene.
inline Image renderOnCpu(const Scene& scene, const RenderSettings& settings, std::uint32_t frames = 1) {
    auto backend = createRenderer("cpu");
    renderFrames(*backend, scene, settings, frames);
    return backend->image();
}

}  // namespace photon::test
