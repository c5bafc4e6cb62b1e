// What photon-bench measures: scenes by name, and per scene its cases (settings and a label) from
// the lists of the command line.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/scene/scene.h"

namespace photon {

// "cornell" (built in), "mesh:N" and "mesh-glass:N" (tools/bench_scenes.h: N triangles),
// "smoke:N" (scenes/smoke.json with its plume made by code, N voxels across), a
// path with an extension (a scene or model file), or a name in the scenes folder.
Scene sceneNamed(const std::string& name, const std::string& scenesDir);

// The lists the cases are made from, each checked as it is parsed, before anything is measured.
struct CaseLists {
    std::optional<Estimator> estimator;  // --estimator's; none: what a render of many frames would choose
    std::vector<std::pair<std::uint32_t, std::uint32_t>> resolutions;
    std::vector<std::uint32_t> photons;
    std::vector<std::uint32_t> gridSweep;  // when given, the only cases: grid builds at 320x240
    std::vector<std::string> vary;         // KEY=V1,V2,...
    bool launchSweep = false;
};

// The photon counts of a comma-separated list, each checked with the scene files' range.
std::vector<std::uint32_t> photonCounts(const std::string& list, const char* flag);

// The estimator of the case: --estimator's, else the one a render of many frames would choose.
void chooseEstimator(RenderSettings& s, const CaseLists& lists);

// What to measure: settings and a label, per scene.
struct Case {
    RenderSettings settings;
    std::string variant;
    bool launchSweep = false;
};

// The cases of `scene`: every resolution × photon count (or only the grid sweep's counts), each
// --vary multiplying them by its values.
std::vector<Case> casesFor(const Scene& scene, const CaseLists& lists);

}  // namespace photon
