#include "core/frame/scene_settings.h"

#include <algorithm>
#include <string>

#include "core/frame/frame_setup.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"

namespace photon {
namespace {

[[noreturn]] void sceneFail(const std::string& where, const std::string& reason) { throw InputError(where + ": " + reason); }

}  // namespace

void chooseSpectral(RenderSettings& settings, const Scene& scene) {
    if (isGiven(settings, "spectral")) {
        return;
    }
    settings.spectral = std::any_of(scene.materials.begin(), scene.materials.end(),
                                    [](const Material& m) { return m.dispersion > 0.0f; });
}

void validateForScene(const RenderSettings& settings, const Scene& scene, const FrameRadii& radii) {
    glm::vec3 extent = scene.boundsMax - scene.boundsMin;
    double size = std::max({double(extent.x), double(extent.y), double(extent.z)});
    const Range& radiusRange = findSetting("radius")->range;
    for (std::uint32_t map = 0; map < MAP_COUNT; ++map) {
        double r = radii.radius[map];
        std::string what = std::string(mapRadiusFlag(map)) + " " + formatNumber(r) + (mapRadius(settings, map) > 0.0f ? "" : " (automatic)");
        if (!radiusRange.contains(r)) {
            if (mapRadius(settings, map) > 0.0f) {
                sceneFail(what, "must be " + radiusRange.describe() + "; the scene spans " + formatNumber(size));
            }
            // Nobody gave this radius: the scene is at fault, not an option.
            sceneFail(scene.name.empty() ? std::string("the scene") : scene.name,
                 "its extent (" + describeSpan(scene.boundsMin, scene.boundsMax) + ") gives an automatic " +
                     mapRadiusFlag(map) + " of " + formatNumber(r) + ", outside " + radiusRange.describe() +
                     " (Photon renders scenes up to " + formatNumber(kMaxSceneSpan) + " wide)");
        }
        if (settings.grid == GridKind::Bounded) {
            double cell = size / double(settings.gridResolution);
            double reach = boundedGridReachCells(map);
            if (r > reach * cell * (1.0 + 1e-6)) {
                sceneFail(what, "too large for the bounded grid, whose cells are " + formatNumber(cell) + " wide: at most " +
                               formatNumber(reach) +
                               " cells (lower --grid-resolution for wider cells, or use --grid hashed)");
            }
        }
    }
}

}  // namespace photon
