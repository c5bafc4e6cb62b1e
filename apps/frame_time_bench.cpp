#include "apps/frame_time_bench.h"

#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "apps/cuda_launch_bench.h"
#include "apps/render_options.h"
#include "core/render/scene_stats.h"
#include "core/frame/buffers.h"
#include "core/frame/median.h"
#include "core/system/output_file.h"
#include "core/system/parallel.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;

struct Row {
    std::string scene;
    std::string backend;
    std::string device;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint32_t photons = 0;
    std::string variant;         // launch configuration or grid build, when swept
    StageTimes median;           // per-stage medians
    double frameMs = 0.0;        // median of per-frame totals
    double storedPhotons = 0.0;  // both maps, last frame
    double firstImageMs = 0.0;   // backend creation → first image on the host
    std::uint64_t triangles = 0;
    double primaryRaysPerSecond = 0.0;  // --primary-rays, CUDA
};

// The scene's triangles and how its hierarchy was built.
void printSceneCost(const std::string& name, const Scene& scene) {
    nlohmann::json j = sceneStatsJson(scene);
    const BvhStats& b = scene.bvh;
    double rate = b.buildSeconds > 0 ? double(b.primitives) / b.buildSeconds / 1e6 : 0.0;
    std::printf("  %s: %zu triangles, %u BVH primitives; BVH built in %.3f s (%.1f M primitives/s, %.2f M/s per core "
                "on %zu), %u binary nodes, depth %u, SAH cost %.1f; %u wide nodes, depth %u, SAH cost %.1f; %.0f bytes per "
                "triangle, scene %s\n",
                name.c_str(), scene.triangles.size(), b.primitives, b.buildSeconds, rate,
                rate / double(workerThreads()), std::size_t(workerThreads()), b.nodes, b.depth, b.sahCost, b.wideNodes,
                b.wideDepth, b.wideSahCost, j.value("bytes_per_triangle", 0.0), formatMiB(j["total_bytes"].get<std::uint64_t>()).c_str());
    std::fflush(stdout);
}

double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

Row measure(Renderer& backend, const Scene& scene, RenderSettings settings, std::uint32_t warmup, std::uint32_t frames,
            Clock::time_point created, bool verbose) {
    backend.setScene(scene);
    backend.setSettings(settings);
    // A real-time frame is one a person sees: with the denoiser on, every frame runs it.
    backend.setDenoiseEachFrame(true);
    Row row;
    row.backend = backend.name();
    row.device = backend.deviceName();
    row.width = settings.width;
    row.height = settings.height;
    row.photons = settings.photons;
    double toReady = msSince(created);
    backend.prepare();
    double toPrepared = msSince(created);
    backend.renderFrame();
    double toFrame = msSince(created);
    backend.image();
    row.firstImageMs = msSince(created);
    if (verbose) {
        std::printf("  first image of %s: backend created %.1f ms, scene uploaded and buffers allocated %.1f ms, "
                    "first frame %.1f ms, image on the host %.1f ms\n",
                    row.backend.c_str(), toReady, toPrepared, toFrame, row.firstImageMs);
    }
    for (std::uint32_t f = 1; f < warmup; ++f) {
        backend.renderFrame();
    }
    std::vector<double> stage[STAGE_COUNT];
    std::vector<double> total;
    for (std::uint32_t f = 0; f < frames; ++f) {
        backend.renderFrame();
        const StageTimes& t = backend.lastFrameStats().ms;
        for (const StageInfo& s : kStages) {
            stage[s.id].push_back(t[s.id]);
        }
        total.push_back(t.total());
    }
    for (const StageInfo& s : kStages) {
        row.median[s.id] = median(stage[s.id]);
    }
    row.frameMs = median(total);
    const FrameStats& s = backend.lastFrameStats();
    row.storedPhotons = double(s.storedPhotons());
    return row;
}

// Photon paths per millisecond of the photon pass, and stored photons per millisecond of the grid
// build (0 without a time).
double photonsPerMs(const Row& r) {
    double ms = r.median[STAGE_TRACE_PHOTONS];
    return ms > 0 ? r.photons / ms : 0.0;
}
double gridPhotonsPerMs(const Row& r) {
    double ms = r.median[STAGE_BUILD_GRID];
    return ms > 0 ? r.storedPhotons / ms : 0.0;
}

void printHeader() {
    std::printf("%-9s %-7s %-10s %9s %-26s", "scene", "backend", "resolution", "photons", "variant");
    for (const StageInfo& s : kStages) {
        std::printf(" %9s", s.label);
    }
    std::printf(" %9s %9s %9s\n", "frame ms", "Mphot/s", "grid G/s");
}

void printRow(const Row& r) {
    std::printf("%-9s %-7s %4ux%-5u %9u %-26s", r.scene.c_str(), r.backend.c_str(), r.width, r.height, r.photons,
                r.variant.c_str());
    for (const StageInfo& s : kStages) {
        std::printf(" %9.3f", r.median[s.id]);
    }
    std::printf(" %9.3f %9.1f %9.2f\n", r.frameMs, photonsPerMs(r) / 1e3, gridPhotonsPerMs(r) / 1e6);
    std::fflush(stdout);
}

nlohmann::json toJson(const Row& r) {
    nlohmann::json stages;
    for (const StageInfo& s : kStages) {
        stages[s.name] = r.median[s.id];
    }
    return {{"scene", r.scene},
            {"backend", r.backend},
            {"device", r.device},
            {"width", r.width},
            {"height", r.height},
            {"photons", r.photons},
            {"variant", r.variant},
            {"stages_ms", stages},
            {"frame_ms", r.frameMs},
            {"stored_photons", r.storedPhotons},
            {"photons_per_second", photonsPerMs(r) * 1e3},
            {"grid_photons_per_second", gridPhotonsPerMs(r) * 1e3},
            {"first_image_ms", r.firstImageMs},
            {"triangles", r.triangles},
            {"primary_rays_per_second", r.primaryRaysPerSecond}};
}

void writeOutputs(const std::vector<Row>& rows, const std::string& jsonPath, const std::string& csvPath,
                  double processToFirstImageMs) {
    if (!jsonPath.empty()) {
        nlohmann::json j;
        j["process_start_to_first_image_ms"] = processToFirstImageMs;
        // The stages in the order a frame runs them (the keys of stages_ms come out sorted).
        j["stages"] = nlohmann::json::array();
        for (const StageInfo& s : kStages) {
            j["stages"].push_back(s.name);
        }
        j["rows"] = nlohmann::json::array();
        for (const Row& r : rows) {
            j["rows"].push_back(toJson(r));
        }
        writeOutputFile(jsonPath, j.dump(2) + "\n", "JSON table");
    }
    if (!csvPath.empty()) {
        std::ostringstream csv;
        csv << "scene,backend,device,width,height,photons,variant,";
        for (const StageInfo& s : kStages) {
            csv << s.name << ",";
        }
        csv << "frame_ms,stored_photons,first_image_ms\n";
        for (const Row& r : rows) {
            csv << r.scene << "," << r.backend << ",\"" << r.device << "\"," << r.width << "," << r.height << ","
                << r.photons << "," << r.variant << ",";
            for (const StageInfo& s : kStages) {
                csv << r.median[s.id] << ",";
            }
            csv << r.frameMs << "," << r.storedPhotons << "," << r.firstImageMs << "\n";
        }
        writeOutputFile(csvPath, csv.str(), "CSV table");
    }
}

}  // namespace

void benchFrameTimes(const BenchOptions& o, const CaseLists& lists, Clock::time_point processStart) {
    std::vector<Row> rows;
    double processToFirstImage = 0.0;
    printHeader();
    for (const std::string& backendName : splitList(o.backends)) {
        Clock::time_point created = Clock::now();
        if (rows.empty()) {
            std::printf("  process start to backend creation: %.1f ms\n", msSince(processStart));
        }
        std::unique_ptr<Renderer> backend = createRenderer(backendName, o.options);
        bool cpu = backendName == "cpu";
        for (const std::string& sceneName : splitList(o.scenes)) {
            Scene scene = sceneNamed(sceneName, o.scenesDir);
            printSceneCost(sceneName, scene);
            auto add = [&](const RenderSettings& s, const std::string& variant) {
                Row r = measure(*backend, scene, s, cpu ? 1 : o.warmup, cpu ? o.cpuFrames : o.frames, created, rows.empty());
                r.scene = sceneName;
                r.variant = variant;
                r.triangles = scene.triangles.size();
                if (o.primaryRays && backendName == "cuda") {
                    r.primaryRaysPerSecond = timePrimaryRays(*backend, s.width, s.height);
                }
                if (processToFirstImage == 0.0) {
                    processToFirstImage =
                        r.firstImageMs + std::chrono::duration<double, std::milli>(created - processStart).count();
                }
                created = Clock::now();
                printRow(r);
                rows.push_back(r);
            };
            for (const Case& c : casesFor(scene, lists)) {
                if (c.launchSweep && backendName == "cuda") {
                    sweepLaunchShapes(*backend, [&](const std::string& shape) { add(c.settings, shape); });
                } else {
                    add(c.settings, c.variant);
                }
                if (o.readback && backendName == "cuda") {
                    timeReadback(*backend);
                }
            }
        }
    }
    std::printf("process start to first image: %.1f ms\n", processToFirstImage);
    writeOutputs(rows, o.jsonPath, o.csvPath, processToFirstImage);
}

}  // namespace photon
