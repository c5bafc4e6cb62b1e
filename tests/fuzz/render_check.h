// What every fuzz target does with a scene it loaded: renders it, tiny (by default 4×4 pixels,
// 2000 photon paths, at most 2 frames, on the CPU backend), so that what was loaded (texture coordinates, textures,
// normals, materials, lights, cameras) is also shaded, under the sanitizers; every pixel must be
// finite. A refusal on the way (InputError: a radius the scene cannot hold, no lights) is fine;
// a non-finite pixel aborts, for libFuzzer to keep the input. PHOTON_FUZZ_TRACE=1 says which.
#pragma once

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "core/frame/renderer.h"
#include "core/image/image.h"
#include "core/scene/scene.h"
#include "core/settings/settings.h"
#include "cpu/cpu_device.h"

namespace photon::fuzz {

inline void renderTiny(const Scene& scene, RenderSettings settings, std::uint32_t width = 4, std::uint32_t height = 4,
                       std::uint32_t photons = 2000) {
    settings.width = std::min(settings.width, width);
    settings.height = std::min(settings.height, height);
    settings.photons = std::min(settings.photons, photons);
    settings.frames = std::min(settings.frames, 2u);
    settings.gatherRays = std::min(settings.gatherRays, 4u);
    settings.lightSamples = std::min(settings.lightSamples, 2u);
    settings.gridResolution = std::min(settings.gridResolution, 64u);
    std::vector<std::unique_ptr<Device>> devices;
    devices.push_back(createCpuDevice());
    Renderer renderer(std::move(devices));
    renderer.setScene(scene);
    renderer.setSettings(settings);
    for (std::uint32_t f = 0; f < settings.frames; ++f) {
        renderer.renderFrame();
    }
    if (!allFinite(renderer.image())) {
        std::fprintf(stderr, "fuzz: a non-finite pixel\n");
        std::abort();
    }
    if (std::getenv("PHOTON_FUZZ_TRACE")) {
        std::fprintf(stderr, "rendered %ux%u, %u photons, %zu triangles, %zu textures\n", settings.width, settings.height,
                     settings.photons, scene.triangles.size(), scene.textures.size());
    }
}

}  // namespace photon::fuzz
