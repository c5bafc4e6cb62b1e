#include "apps/photon_use_bench.h"

#include <cstdio>

#include "core/frame/photon_use.h"
#include "core/settings/setting_specs.h"

namespace photon {

void benchPhotonUse(Renderer& backend, const std::vector<std::pair<Scene, PhotonUseCase>>& cases, std::uint32_t frames) {
    std::printf("%-10s %-8s %-11s %9s %-8s %10s %10s %8s %9s\n", "scene", "backend", "resolution", "photons", "map",
                "stored", "gathered", "share", "pixels");
    for (const auto& [scene, c] : cases) {
        backend.setScene(scene);
        backend.setSettings(c.settings);
        for (std::uint32_t f = 0; f < frames; ++f) {
            backend.renderFrame();
        }
        PhotonUse use = measurePhotonUse(backend);
        std::string resolution = std::to_string(c.settings.width) + "x" + std::to_string(c.settings.height);
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            double share = use.stored[m] > 0 ? double(use.gathered[m]) / double(use.stored[m]) : 0.0;
            std::printf("%-10s %-8s %-11s %9u %-8s %10llu %10llu %7.1f%% %9llu\n", c.scene.c_str(), backend.name().c_str(),
                        resolution.c_str(), c.settings.photons, kMapNames[m], (unsigned long long)use.stored[m],
                        (unsigned long long)use.gathered[m], 100.0 * share, (unsigned long long)use.discs[m]);
        }
    }
}

}  // namespace photon
