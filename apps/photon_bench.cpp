// photon-bench: frame and per-stage times over scenes × resolutions × photons per frame ×
// backends. Times are the backends' own stage timers (CUDA events, Vulkan timestamps, a steady
// clock on the CPU), medians over timed frames after warm-up frames. Prints a table; writes
// JSON and CSV for tools/plot_bench.py.
//
//   photon-bench --backends cpu,cuda --scenes cornell --resolutions 640x480,1920x1080
//                --photons 1000000 --frames 20 --warmup 3 --json bench.json --csv bench.csv
//   photon-bench --grid-sweep 1000000,2000000,4000000,8000000,16000000   (grid build rate)
//   photon-bench --backends cuda --scenes mesh:10000,mesh:1000000,mesh:10000000 --primary-rays
//                (cost over triangle count: BVH build, primary rays, photon paths, frames)
//   photon-bench --image-writers [--resolutions 1920x1080,3840x2160 --writes 11 --image-dir DIR]
//                (each image format and EXR compression of one rendered frame: size and write time)
//   photon-bench --bvh-builds 7 --scenes mesh:100000,mesh:1000000 --threads 1,0
//                (the BVH build alone: median time, its phases and the SAH cost; no frames)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/render/devices.h"
#include "apps/image_writer_bench.h"
#include "apps/photon_use_bench.h"
#include "apps/render_options.h"
#include "apps/scene_stats.h"
#include "core/frame/buffers.h"
#include "core/frame/median.h"
#include "core/loaders/scene_loader.h"
#include "core/scene/bvh.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "core/system/output_file.h"
#include "core/system/parallel.h"
#include "core/system/program.h"
#include "tools/bench_scenes.h"
#ifdef PHOTON_HAVE_CUDA
#include "cuda/cuda_backend.h"
#endif

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;
const Clock::time_point kProcessStart = Clock::now();

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

// "cornell" (built in), "mesh:N" and "mesh-glass:N" (tools/bench_scenes.h: N triangles), a
// path with an extension (a scene or model file), or a name in the scenes folder.
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
    if (name.find('.') != std::string::npos) {
        return loadSceneFile(name);
    }
    return loadSceneFile(scenesDir + "/" + name + ".json");
}

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

// Builds the scene's hierarchy `builds` times on each thread count (0: all) and prints the
// median build and its phases, with the tree's size and SAH cost (the same for every count).
nlohmann::json benchBvhBuilds(const std::string& name, const Scene& scene, std::uint32_t builds,
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

double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

Row measure(Backend& backend, const Scene& scene, RenderSettings settings, std::uint32_t warmup, std::uint32_t frames,
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

// Runs `measure` once per CUDA launch shape (threads per photon block, pixel tile).
// Each shape starts from the backend's own configuration (its gridBlocks follow the device's SMs).
void sweepLaunchShapes([[maybe_unused]] Backend& backend, [[maybe_unused]] const std::function<void(const std::string&)>& measure) {
#ifdef PHOTON_HAVE_CUDA
    const LaunchConfig start = cudaLaunchConfig(backend);
    for (std::uint32_t photonBlock : {64u, 128u, 256u}) {
        for (auto [bx, by] : {std::pair{8u, 8u}, {16u, 8u}, {32u, 4u}, {16u, 16u}, {32u, 8u}}) {
            LaunchConfig c = start;
            c.photonBlock = photonBlock;
            c.pixelBlockX = bx;
            c.pixelBlockY = by;
            setCudaLaunchConfig(backend, c);
            measure(std::to_string(photonBlock) + "/" + std::to_string(bx) + "x" + std::to_string(by));
        }
    }
    setCudaLaunchConfig(backend, start);
#endif
}

// The CUDA backend's readback through pageable memory instead of pinned (no effect elsewhere).
void setPageableReadback([[maybe_unused]] Backend& backend, [[maybe_unused]] bool pageable) {
#ifdef PHOTON_HAVE_CUDA
    LaunchConfig c = cudaLaunchConfig(backend);
    c.pinnedReadback = !pageable;
    setCudaLaunchConfig(backend, c);
#endif
}

// Median host time of Backend::image() (a synchronous copy of the accumulated image), through
// pinned memory and straight into pageable memory.
void timeReadback(Backend& backend) {
    for (bool pinned : {true, false}) {
        setPageableReadback(backend, !pinned);
        std::vector<double> ms;
        for (int i = 0; i < 21; ++i) {
            Clock::time_point t = Clock::now();
            Image image = backend.image();
            ms.push_back(msSince(t));
        }
        std::printf("  image readback (%s memory): %.2f ms median of 21\n", pinned ? "pinned" : "pageable", median(ms));
    }
    setPageableReadback(backend, false);
}

int run(int argc, char** argv) {
    CLI::App app{"Photon benchmark: per-stage times over scenes, resolutions, photon counts and backends",
                 "photon-bench"};
    std::string backends = "cpu";
    std::string scenes = "cornell";
    std::string scenesDir = PHOTON_SCENES_DIR;
    std::string resolutions = "640x480,800x600,1024x768,1280x720,1920x1080,2560x1600,3840x2400";
    std::string photons = "1000000";
    std::string estimator;  // empty: what a render of many frames of the scene gets (chooseDefaults)
    std::vector<std::string> vary;
    std::string gridSweep;
    std::string jsonPath;
    std::string csvPath;
    std::uint32_t frames = 20;
    std::uint32_t warmup = 3;
    std::uint32_t cpuFrames = 3;
    bool launchSweep = false;
    bool readback = false;
    bool primaryRays = false;
    bool imageWriters = false;
    std::uint32_t writes = 11;
    std::uint32_t photonUse = 0;
    std::string imageDir = ".";
    std::uint32_t bvhBuilds = 0;
    std::string threads = "0";
    BackendOptions options;
    app.add_option("--backends", backends, "Comma-separated: cpu,cuda,vulkan");
    app.add_option("--scenes", scenes, "Comma-separated scene names (files in --scenes-dir; cornell is built in)");
    app.add_option("--scenes-dir", scenesDir, "Where scene files are")->check(kFileName);
    app.add_option("--resolutions", resolutions, "Comma-separated WIDTHxHEIGHT");
    app.add_option("--photons", photons, "Comma-separated photon paths per frame");
    app.add_option("--estimator", estimator, "Radiance estimate: " + choices(Estimator{}) + " (default: a render's, sppm unless the scene says)");
    app.add_option("--frames", frames, "Timed frames per measurement (GPU backends)")->check(CLI::Range(1u, 100000u));
    app.add_option("--cpu-frames", cpuFrames, "Timed frames per measurement on the CPU")->check(CLI::Range(1u, 1000u));
    app.add_option("--warmup", warmup, "Untimed frames first")->check(CLI::Range(1u, 1000u));
    app.add_option("--vary", vary, "KEY=V1,V2,...: also measure each value of a scene-file render setting "
                                   "(cell_size, gather_budget, radius, caustic_radius, caustic_fraction, estimator, ...)");
    app.add_option("--grid-sweep", gridSweep, "Comma-separated photon counts: grid build rate at 320x240");
    addSwitch(app, "--launch-sweep", launchSweep, "CUDA: sweep block shapes of every stage");
    addSwitch(app, "--primary-rays", primaryRays, "CUDA: also time primary rays alone (nearest hit, no shading) per case");
    app.add_option("--bvh-builds", bvhBuilds, "Time only the BVH build of each scene, this many times (no frames)")
        ->check(CLI::Range(1u, 10000u));
    app.add_option("--threads", threads, "With --bvh-builds: comma-separated thread counts to build on (0: all)");
    addSwitch(app, "--readback", readback, "CUDA: time reading the image back through pinned and pageable memory");
    addSwitch(app, "--image-writers", imageWriters, "Time the image files of one frame of the first scene "
                                                  "instead (on the first backend; default resolutions 1920x1080,3840x2160)");
    app.add_option("--writes", writes, "--image-writers: timed writes of each file")->check(CLI::Range(1u, 1000u));
    app.add_option("--image-dir", imageDir, "--image-writers: the folder to write them in")->check(kFileName);
    app.add_option("--photon-use", photonUse, "Render this many frames of each case on the first backend and print the "
                                              "share of the last frame's stored photons that some pixel gathers (no times)")
        ->check(CLI::Range(1u, 100000u));
    app.add_option("--device", options.device, "GPU to use");
    app.add_option("--json", jsonPath, "Write the rows as JSON")->check(kFileName);
    app.add_option("--csv", csvPath, "Write the rows as CSV")->check(kFileName);
    if (int code = parseCommandLine(app, argc, argv); code >= 0) {
        return code;
    }
    std::optional<Estimator> given;
    if (!estimator.empty()) {
        RenderSettings checked;
        setSetting(checked, *findSetting("estimator"), estimator, "--estimator");
        given = checked.estimator;
    }
    // The estimator of the case: --estimator's, else the one a render of many frames would choose.
    auto chooseEstimator = [&](RenderSettings& s) {
        if (given) {
            s.estimator = *given;
        } else {
            chooseDefaults(s, true);
        }
    };
    // Every list value is checked now, with the scene files' ranges, before anything is measured.
    auto photonCounts = [&](const std::string& list, const char* flag) {
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
    };
    std::vector<std::uint32_t> photonList = photonCounts(photons, "--photons");
    std::vector<std::uint32_t> gridSweepList;
    if (!gridSweep.empty()) {
        gridSweepList = photonCounts(gridSweep, "--grid-sweep");
    }
    if (imageWriters && app.count("--resolutions") == 0) {
        resolutions = "1920x1080,3840x2160";
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> resolutionList;
    for (const std::string& r : splitList(resolutions)) {
        resolutionList.push_back(parseImageSize(r, "--resolutions"));
    }
    if (resolutionList.empty()) {
        throw InputError("--resolutions: expected a comma-separated list of WIDTHxHEIGHT");
    }
    if (!jsonPath.empty()) {
        checkOutputPath(jsonPath, "JSON table");
    }
    if (!csvPath.empty()) {
        checkOutputPath(csvPath, "CSV table");
    }

    if (imageWriters) {
        checkOutputPath(imageDir + "/photon-bench-image.png", "image");
        std::vector<std::string> names = splitList(backends);
        std::unique_ptr<Backend> backend = createBackend(names.empty() ? "cpu" : names[0], options);
        std::vector<std::string> sceneNames = splitList(scenes);
        benchImageWriters(*backend, sceneNamed(sceneNames.empty() ? "cornell" : sceneNames[0], scenesDir),
                          resolutionList, writes, imageDir);
        return 0;
    }

    if (photonUse > 0) {
        std::vector<std::string> names = splitList(backends);
        std::unique_ptr<Backend> backend = createBackend(names.empty() ? "cpu" : names[0], options);
        std::vector<std::pair<Scene, PhotonUseCase>> cases;
        for (const std::string& name : splitList(scenes)) {
            Scene scene = sceneNamed(name, scenesDir);
            for (auto [width, height] : resolutionList) {
                for (std::uint32_t n : photonList) {
                    RenderSettings s = scene.render;
                    chooseEstimator(s);
                    s.width = width;
                    s.height = height;
                    s.photons = n;
                    cases.emplace_back(scene, PhotonUseCase{name, s});
                }
            }
        }
        benchPhotonUse(*backend, cases, photonUse);
        return 0;
    }

    // What to measure: settings and a label, per scene.
    struct Case {
        RenderSettings settings;
        std::string variant;
        bool launchSweep = false;
    };
    auto casesFor = [&](const Scene& scene) {
        RenderSettings base = scene.render;
        chooseEstimator(base);
        base.frames = 1;
        std::vector<Case> cases;
        if (!gridSweepList.empty()) {
            for (std::uint32_t n : gridSweepList) {
                RenderSettings s = base;
                s.width = 320;
                s.height = 240;
                s.photons = n;
                cases.push_back({s, "grid"});
            }
            return cases;
        }
        for (auto [width, height] : resolutionList) {
            for (std::uint32_t n : photonList) {
                RenderSettings s = base;
                s.width = width;
                s.height = height;
                s.photons = n;
                cases.push_back({s, "", launchSweep});
            }
        }
        // Each --vary multiplies the cases by its values.
        for (const std::string& v : vary) {
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
    };

    if (bvhBuilds > 0) {
        std::vector<unsigned> threadCounts;
        for (const std::string& t : splitList(threads)) {
            std::size_t end = 0;
            unsigned long n = 0;
            try {
                n = std::stoul(t, &end);
            } catch (const std::exception&) {
                end = 0;
            }
            if (end == 0 || end != t.size() || n > 4096) {
                throw InputError("--threads: " + quote(t) + " is not a thread count (0: all)");
            }
            threadCounts.push_back(unsigned(n));
        }
        std::printf("%-16s %10s %7s %9s %9s %8s %8s %8s %8s %8s %8s %8s %9s %5s %9s %9s %5s %9s\n", "scene", "prims",
                    "threads", "median s", "min s", "M/s", "M/s/core", "prepare", "top", "subtrees", "flatten", "widen",
                    "nodes", "depth", "SAH", "wide", "depth", "wide SAH");
        nlohmann::json rows = nlohmann::json::array();
        for (const std::string& sceneName : splitList(scenes)) {
            Scene scene = sceneNamed(sceneName, scenesDir);  // built once by its finalize: a warm-up
            for (nlohmann::json& r : benchBvhBuilds(sceneName, scene, bvhBuilds, threadCounts)) {
                rows.push_back(r);
            }
        }
        if (!jsonPath.empty()) {
            writeOutputFile(jsonPath, nlohmann::json{{"bvh_builds", rows}}.dump(2) + "\n", "JSON table");
        }
        return 0;
    }

    std::vector<Row> rows;
    double processToFirstImage = 0.0;
    printHeader();
    for (const std::string& backendName : splitList(backends)) {
        Clock::time_point created = Clock::now();
        if (rows.empty()) {
            std::printf("  process start to backend creation: %.1f ms\n", msSince(kProcessStart));
        }
        std::unique_ptr<Backend> backend = createBackend(backendName, options);
        bool cpu = backendName == "cpu";
        for (const std::string& sceneName : splitList(scenes)) {
            Scene scene = sceneNamed(sceneName, scenesDir);
            printSceneCost(sceneName, scene);
            auto add = [&](const RenderSettings& s, const std::string& variant) {
                Row r = measure(*backend, scene, s, cpu ? 1 : warmup, cpu ? cpuFrames : frames, created, rows.empty());
                r.scene = sceneName;
                r.variant = variant;
                r.triangles = scene.triangles.size();
#ifdef PHOTON_HAVE_CUDA
                if (primaryRays && backendName == "cuda") {
                    PrimaryRayTiming t = timeCudaPrimaryRays(*backend, 21);
                    r.primaryRaysPerSecond = t.medianMs > 0 ? double(t.rays) / t.medianMs * 1e3 : 0.0;
                    std::printf("  primary rays %ux%u: %.3f ms median of 21, %.2f G rays/s, %.1f%% hit\n", s.width,
                                s.height, t.medianMs, r.primaryRaysPerSecond / 1e9,
                                t.rays ? 100.0 * double(t.hits) / double(t.rays) : 0.0);
                }
#endif
                if (processToFirstImage == 0.0) {
                    processToFirstImage =
                        r.firstImageMs + std::chrono::duration<double, std::milli>(created - kProcessStart).count();
                }
                created = Clock::now();
                printRow(r);
                rows.push_back(r);
            };
            for (const Case& c : casesFor(scene)) {
                if (c.launchSweep && backendName == "cuda") {
                    sweepLaunchShapes(*backend, [&](const std::string& shape) { add(c.settings, shape); });
                } else {
                    add(c.settings, c.variant);
                }
                if (readback && backendName == "cuda") {
                    timeReadback(*backend);
                }
            }
        }
    }
    std::printf("process start to first image: %.1f ms\n", processToFirstImage);
    writeOutputs(rows, jsonPath, csvPath, processToFirstImage);
    return 0;
}

}  // namespace
}  // namespace photon

int main(int argc, char** argv) {
    return photon::runProgram("photon-bench", [&] { return photon::run(argc, argv); });
}
