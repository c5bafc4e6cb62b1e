#include "apps/bench_cases.h"

#include "apps/render_options.h"
#include "core/loaders/scene_loader.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "tools/bench_scenes.h"

namespace photon {

Scene sceneNamed(const std::string& name, const std::string& scenesDir) {
    if (name == "cornell") {
        return defaultScene();
    }
    for (const char* prefix : {"mesh:", "mesh-glass:"}) {
        std::string p = prefix;
        if (name.compare(0, p.size(), p) == 0) {
            RenderSettings s;
            setSetting(s, *findSetting("photons"), name.substr(p.size()), "--scenes");  // an integer in range
            return tools::meshBenchScene(std::stoull(name.substr(p.size())), p == "mesh-glass:");
        }
    }
    if (name.compare(0, 6, "smoke:") == 0) {
        std::string n = name.substr(6);
        if (n.empty() || n.size() > 3 || n.find_first_not_of("0123456789") != std::string::npos || std::stoul(n) < 1 ||
            std::stoul(n) > kDensityResolutionMax / 2) {
            throw InputError("--scenes: " + name + ": expected smoke:N, N voxels across the plume from 1 to " +
                             std::to_string(kDensityResolutionMax / 2));
        }
        return tools::smokeBenchScene(scenesDir, std::uint32_t(std::stoul(n)));
    }
    if (name.find('.') != std::string::npos) {
        return loadSceneFile(name);
    }
    return loadSceneFile(scenesDir + "/" + name + ".json");
}

std::vector<std::uint32_t> photonCounts(const std::string& list, const char* flag) {
    std::vector<std::uint32_t> counts;
    for (const std::string& n : splitList(list)) {
        RenderSettings s;
        setSetting(s, *findSetting("photons"), n, flag);
        counts.push_back(s.photons);
    }
    if (counts.empty()) {
        throw InputError(std::string(flag) + ": expected a comma-separated list of photon counts");
    }
    return counts;
}

void chooseEstimator(RenderSettings& s, const CaseLists& lists) {
    if (lists.estimator) {
        s.estimator = *lists.estimator;
    } else {
        chooseDefaults(s, true);
    }
}

std::vector<Case> casesFor(const Scene& scene, const CaseLists& lists) {
    RenderSettings base = scene.render;
    chooseEstimator(base, lists);
    base.frames = 1;
    std::vector<Case> cases;
    if (!lists.gridSweep.empty()) {
        for (std::uint32_t n : lists.gridSweep) {
            RenderSettings s = base;
            s.width = 320;
            s.height = 240;
            s.photons = n;
            cases.push_back({s, "grid"});
        }
        return cases;
    }
    for (auto [width, height] : lists.resolutions) {
        for (std::uint32_t n : lists.photons) {
            RenderSettings s = base;
            s.width = width;
            s.height = height;
            s.photons = n;
            cases.push_back({s, "", lists.launchSweep});
        }
    }
    // Each --vary multiplies the cases by its values.
    for (const std::string& v : lists.vary) {
        auto eq = v.find('=');
        if (eq == std::string::npos) {
            throw InputError("--vary " + v + ": expected KEY=V1,V2");
        }
        std::string key = v.substr(0, eq);
        std::vector<Case> varied;
        for (const Case& c : cases) {
            for (const std::string& value : splitList(v.substr(eq + 1))) {
                Case d = c;
                applySetting(d.settings, key, value);
                d.variant += (d.variant.empty() ? "" : " ") + key + "=" + value;
                varied.push_back(d);
            }
        }
        cases = varied;
    }
    return cases;
}

}  // namespace photon
