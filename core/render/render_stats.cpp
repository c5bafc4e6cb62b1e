#include "core/render/render_stats.h"

#include "core/render/scene_stats.h"

namespace photon {

nlohmann::json renderStatsJson(Backend& backend) {
    const FrameStats& last = backend.lastFrameStats();
    const RenderSettings& s = backend.settings();
    nlohmann::json j;
    j["backend"] = backend.name();
    j["device"] = backend.deviceName();
    j["scene"] = backend.scene().name;
    j["scene_stats"] = sceneStatsJson(backend.scene());
    j["width"] = s.width;
    j["height"] = s.height;
    j["estimator"] = toString(s.estimator);
    PhotonMaps maps = backend.readPhotonMaps();
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        GridStats g = gridStats(maps.cellStart[m]);
        j["photons"][kMapNames[m]] = {{"emitted_paths", last.emitted[m]},
                                       {"stored", last.stored[m]},
                                       {"capacity", last.capacity[m]},
                                       {"radius", backend.lastFrameParams().grids[m].radius}};
        j["grid"][kMapNames[m]] = {{"kind", toString(s.grid)},
                                    {"cells", g.cells},
                                    {"occupied", g.occupied},
                                    {"max_per_cell", g.maxPerCell},
                                    {"mean_per_occupied", g.meanPerOccupied}};
    }
    if (backend.scene().environmentLight != NONE) {
        // How well the bounding sphere's disks aim the environment's photons at the scene.
        j["environment"] = {{"source", backend.scene().environment.source.empty() ? "uniform" : backend.scene().environment.source},
                            {"photon_paths", last.environmentPaths},
                            {"photons_hitting_the_scene", last.environmentHits},
                            {"hit_fraction", last.environmentPaths > 0 ? double(last.environmentHits) / last.environmentPaths : 0.0}};
    }
    return j;
}

}  // namespace photon
