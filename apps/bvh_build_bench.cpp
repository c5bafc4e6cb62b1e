#include "apps/bvh_build_bench.h"

#include <algorithm>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "apps/bench_cases.h"
#include "core/frame/median.h"
#include "core/scene/bvh.h"
#include "apps/render_options.h"
#include "core/system/error.h"
#include "core/system/output_file.h"
#include "core/system/parallel.h"

namespace photon {
namespace {

// Builds the scene's hierarchy `builds` times on each thread count (0: all) and prints the
// median build and its phases, with the tree's size and SAH cost (the same for every count).
nlohmann::json timeBuilds(const std::string& name, const Scene& scene, std::uint32_t builds,
                          const std::vector<unsigned>& threadCounts) {
    nlohmann::json rows = nlohmann::json::array();
    for (unsigned threads : threadCounts) {
        setThreadLimit(threads);
        std::vector<double> total, prepare, top, subtrees, flatten, widen;
        BvhStats b;
        for (std::uint32_t i = 0; i < builds; ++i) {
            std::vector<WideBvhNode> nodes;  // new every time, as Scene::finalize's are
            std::vector<std::uint32_t> refs;
            b = buildBvh(scene, nodes, refs);
            total.push_back(b.buildSeconds);
            prepare.push_back(b.prepareSeconds);
            top.push_back(b.topSeconds);
            subtrees.push_back(b.subtreeSeconds);
            flatten.push_back(b.flattenSeconds);
            widen.push_back(b.widenSeconds);
        }
        unsigned used = threadLimit();
        setThreadLimit(0);
        double seconds = median(total);
        double rate = seconds > 0 ? double(b.primitives) / seconds / 1e6 : 0.0;
        double fastest = *std::min_element(total.begin(), total.end());
        std::printf("%-16s %10u %7u %9.4f %9.4f %8.1f %8.2f %8.4f %8.4f %8.4f %8.4f %8.4f %9u %5u %9.2f %9u %5u %9.2f\n",
                    name.c_str(), b.primitives, used, seconds, fastest, rate, rate / used, median(prepare), median(top),
                    median(subtrees), median(flatten), median(widen), b.nodes, b.depth, b.sahCost, b.wideNodes,
                    b.wideDepth, b.wideSahCost);
        std::fflush(stdout);
        rows.push_back({{"scene", name},
                        {"primitives", b.primitives},
                        {"threads", used},
                        {"builds", builds},
                        {"seconds", seconds},
                        {"fastest_seconds", fastest},
                        {"prepare_seconds", median(prepare)},
                        {"top_seconds", median(top)},
                        {"subtree_seconds", median(subtrees)},
                        {"flatten_seconds", median(flatten)},
                        {"widen_seconds", median(widen)},
                        {"nodes", b.nodes},
                        {"leaves", b.leaves},
                        {"depth", b.depth},
                        {"sah_cost", b.sahCost},
                        {"wide_nodes", b.wideNodes},
                        {"wide_depth", b.wideDepth},
                        {"wide_sah_cost", b.wideSahCost},
                        {"stack", b.stack}});
    }
    return rows;
}

}  // namespace

std::vector<unsigned> parseThreadCounts(const std::string& list) {
    std::vector<unsigned> threadCounts;
    for (const std::string& t : splitList(list)) {
        unsigned long n = 0;
        if (!parseWholeNumber(t, n) || n > 4096) {
            throw InputError("--threads: " + quote(t) + " is not a thread count (0: all)");
        }
        threadCounts.push_back(unsigned(n));
    }
    return threadCounts;
}

void benchBvhBuilds(const std::vector<std::string>& scenes, const std::string& scenesDir, std::uint32_t builds,
                    const std::vector<unsigned>& threadCounts, const std::string& jsonPath) {
    std::printf("%-16s %10s %7s %9s %9s %8s %8s %8s %8s %8s %8s %8s %9s %5s %9s %9s %5s %9s\n", "scene", "prims",
                "threads", "median s", "min s", "M/s", "M/s/core", "prepare", "top", "subtrees", "flatten", "widen",
                "nodes", "depth", "SAH", "wide", "depth", "wide SAH");
    nlohmann::json rows = nlohmann::json::array();
    for (const std::string& sceneName : scenes) {
        Scene scene = sceneNamed(sceneName, scenesDir);  // built once by its finalize: a warm-up
        for (nlohmann::json& r : timeBuilds(sceneName, scene, builds, threadCounts)) {
            rows.push_back(r);
        }
    }
    if (!jsonPath.empty()) {
        writeOutputFile(jsonPath, nlohmann::json{{"bvh_builds", rows}}.dump(2) + "\n", "JSON table");
    }
}

}  // namespace photon
