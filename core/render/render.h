// The library face's one entry point: a scene and its settings in, an image out. It picks the
// device (core/render/devices.h), renders frame after frame until the frames or the time are spent
// or the caller cancels, and hands back the image with what a program reports about it. Nothing
// here parses a command line: photon-render is option parsing around render(), and a binding or
// another program calls it the same way.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/frame/aov_images.h"
#include "core/frame/renderer.h"
#include "core/image/image.h"
#include "core/scene/scene.h"

namespace photon {

// How long and where: `seconds` > 0 renders until that much time has passed (at most
// settings.frames frames if `framesCap`), else exactly settings.frames frames.
struct RenderJob {
    std::string backend = "auto";  // auto|cpu|cuda|vulkan, or a list of them, a device each ("cpu,cpu")
    DeviceOptions device;
    double seconds = 0.0;
    bool framesCap = false;
};

// Called on the rendering thread. `frame` after each frame (frames done, seconds since the start);
// `cancel` after each frame: nonzero (a reason: a signal's number, or 1) stops the render, which
// still returns the image so far; under MPI any process's request stops every process.
// `finished` sees the renderer once the last frame is done, before its images are read back (the
// photon maps, the frame parameters: what a statistics file reports).
struct RenderObserver {
    std::function<void(std::uint32_t frames, double seconds)> frame;
    std::function<int()> cancel;
    std::function<void(Renderer& renderer)> finished;
};

struct RenderResult {
    Image image;                    // denoised where the settings say so
    Image raw;                      // the image before the denoiser, where it ran; else empty
    AovImages aovs;                 // where settings.aov
    std::vector<StageTimes> times;  // each frame's stage times
    FrameStats last;                // the last frame's counts and times
    double seconds = 0.0;           // wall time from the device's creation to the image
    int cancelled = 0;              // the largest stop request of any process (0: rendered to the end)
    std::uint32_t processes = 1;    // rendering together (MPI)
    bool leader = true;             // false in the processes of an MPI render but the first: no
                                    // images (and `finished` is not called)
    std::string backend;            // the backend's and the device's names
    std::string device;
};

// Renders `scene` with `settings` (validated: core/settings/settings.h's validateSettings; the
// photon count chosen for the device where the settings leave it). Throws InputError for a bad
// scene or settings and RuntimeError when the device fails.
RenderResult render(Scene scene, RenderSettings settings, const RenderJob& job, const RenderObserver& observer = {});

}  // namespace photon
