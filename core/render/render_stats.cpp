#include "core/render/render_stats.h"

#include "core/render/scene_stats.h"

namespace photon {

nlohmann::json renderStatsJson(Renderer& renderer) {
    const FrameStats& last = renderer.lastFrameStats();
    const RenderSettings& s = renderer.settings();
    nlohmann::json j;
    j["backend"] = renderer.name();
    j["device"] = renderer.deviceName();
    j["scene"] = renderer.scene().name;
    j["scene_stats"] = sceneStatsJson(renderer.scene());
    j["width"] = s.width;
    j["height"] = s.height;
    j["estimator"] = toString(s.estimator);
    PhotonMaps maps = renderer.readPhotonMaps();
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        GridStats g = gridStats(maps.cellStart[m]);
        j["photons"][kMapNames[m]] = {{"emitted_paths", last.emitted[m]},
                                       {"stored", last.stored[m]},
                                       {"capacity", last.capacity[m]},
                                       {"radius", renderer.lastFrameParams().grids[m].radius}};
        j["grid"][kMapNames[m]] = {{"kind", toString(s.grid)},
                                    {"cells", g.cells},
                                    {"occupied", g.occupied},
                                    {"max_per_cell", g.maxPerCell},
                                    {"mean_per_occupied", g.meanPerOccupied}};
    }
    if (renderer.scene().environmentLight != NONE) {
        // How well the bounding sphere's disks aim the environment's photons at the scene.
        j["environment"] = {{"source", renderer.scene().environment.source.empty() ? "uniform" : renderer.scene().environment.source},
                            {"photon_paths", last.environmentPaths},
                            {"photons_hitting_the_scene", last.environmentHits},
                            {"hit_fraction", last.environmentPaths > 0 ? double(last.environmentHits) / last.environmentPaths : 0.0}};
    }
    if (renderer.deviceCount() > 1 || renderer.processes() > 1) {
        // The photons the other devices (and processes) sent to the first one's maps in the last
        // frame (core/frame/collective.h), as the leader received them.
        j["exchange"] = {{"devices", renderer.deviceCount()},
                         {"processes", renderer.processes()},
                         {"bytes", last.exchange.bytes},
                         {"ms", last.exchange.ms}};
    }
    return j;
}

}  // namespace photon
