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
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <CLI/CLI.hpp>

#include "apps/bench_cases.h"
#include "apps/bench_options.h"
#include "apps/bvh_build_bench.h"
#include "apps/frame_time_bench.h"
#include "apps/image_writer_bench.h"
#include "apps/photon_use_bench.h"
#include "apps/render_options.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "core/system/output_file.h"
#include "core/system/program.h"

namespace photon {
namespace {

const std::chrono::steady_clock::time_point kProcessStart = std::chrono::steady_clock::now();

void addOptions(CLI::App& app, BenchOptions& o) {
    app.add_option("--backends", o.backends, "Comma-separated: cpu,cuda,vulkan");
    app.add_option("--scenes", o.scenes, "Comma-separated scene names (files in --scenes-dir; cornell is built in; mesh:N, mesh-glass:N and smoke:N are made by code)");
    app.add_option("--scenes-dir", o.scenesDir, "Where scene files are")->check(kFileName);
    app.add_option("--resolutions", o.resolutions, "Comma-separated WIDTHxHEIGHT");
    app.add_option("--photons", o.photons, "Comma-separated photon paths per frame");
    app.add_option("--estimator", o.estimator, "Radiance estimate: " + choices(Estimator{}) + " (default: a render's, sppm unless the scene says)");
    app.add_option("--frames", o.frames, "Timed frames per measurement (GPU backends)")->check(CLI::Range(1u, 100000u));
    app.add_option("--cpu-frames", o.cpuFrames, "Timed frames per measurement on the CPU")->check(CLI::Range(1u, 1000u));
    app.add_option("--warmup", o.warmup, "Untimed frames first")->check(CLI::Range(1u, 1000u));
    app.add_option("--vary", o.vary, "KEY=V1,V2,...: also measure each value of a scene-file render setting "
                                   "(cell_size, gather_budget, radius, caustic_radius, caustic_fraction, estimator, ...)");
    app.add_option("--grid-sweep", o.gridSweep, "Comma-separated photon counts: grid build rate at 320x240");
    addSwitch(app, "--launch-sweep", o.launchSweep, "CUDA: sweep block shapes of every stage");
    addSwitch(app, "--primary-rays", o.primaryRays, "CUDA: also time primary rays alone (nearest hit, no shading) per case");
    app.add_option("--bvh-builds", o.bvhBuilds, "Time only the BVH build of each scene, this many times (no frames)")
        ->check(CLI::Range(1u, 10000u));
    app.add_option("--threads", o.threads, "With --bvh-builds: comma-separated thread counts to build on (0: all)");
    addSwitch(app, "--readback", o.readback, "CUDA: time reading the image back through pinned and pageable memory");
    addSwitch(app, "--image-writers", o.imageWriters, "Time the image files of one frame of the first scene "
                                                  "instead (on the first backend; default resolutions 1920x1080,3840x2160)");
    app.add_option("--writes", o.writes, "--image-writers: timed writes of each file")->check(CLI::Range(1u, 1000u));
    app.add_option("--image-dir", o.imageDir, "--image-writers: the folder to write them in")->check(kFileName);
    app.add_option("--photon-use", o.photonUse, "Render this many frames of each case on the first backend and print the "
                                              "share of the last frame's stored photons that some pixel gathers (no times)")
        ->check(CLI::Range(1u, 100000u));
    app.add_option("--device", o.options.device, "GPU to use");
    app.add_option("--json", o.jsonPath, "Write the rows as JSON")->check(kFileName);
    app.add_option("--csv", o.csvPath, "Write the rows as CSV")->check(kFileName);
}

// The lists of the options, each value checked (with the scene files' ranges) before anything
// is measured.
CaseLists parseLists(const CLI::App& app, BenchOptions& o) {
    CaseLists lists;
    if (!o.estimator.empty()) {
        RenderSettings checked;
        setSetting(checked, *findSetting("estimator"), o.estimator, "--estimator");
        lists.estimator = checked.estimator;
    }
    lists.photons = photonCounts(o.photons, "--photons");
    if (!o.gridSweep.empty()) {
        lists.gridSweep = photonCounts(o.gridSweep, "--grid-sweep");
    }
    if (o.imageWriters && app.count("--resolutions") == 0) {
        o.resolutions = "1920x1080,3840x2160";
    }
    for (const std::string& r : splitList(o.resolutions)) {
        lists.resolutions.push_back(parseImageSize(r, "--resolutions"));
    }
    if (lists.resolutions.empty()) {
        throw InputError("--resolutions: expected a comma-separated list of WIDTHxHEIGHT");
    }
    lists.vary = o.vary;
    lists.launchSweep = o.launchSweep;
    return lists;
}

// The first backend of --backends (cpu when none), for the jobs that run on one.
std::unique_ptr<Renderer> firstBackend(const BenchOptions& o) {
    std::vector<std::string> names = splitList(o.backends);
    return createRenderer(names.empty() ? "cpu" : names[0], o.options);
}

void runImageWriters(const BenchOptions& o, const CaseLists& lists) {
    checkOutputPath(o.imageDir + "/photon-bench-image.png", "image");
    std::unique_ptr<Renderer> backend = firstBackend(o);
    std::vector<std::string> sceneNames = splitList(o.scenes);
    benchImageWriters(*backend, sceneNamed(sceneNames.empty() ? "cornell" : sceneNames[0], o.scenesDir),
                      lists.resolutions, o.writes, o.imageDir);
}

void runPhotonUse(const BenchOptions& o, const CaseLists& lists) {
    std::unique_ptr<Renderer> backend = firstBackend(o);
    std::vector<std::pair<Scene, PhotonUseCase>> cases;
    for (const std::string& name : splitList(o.scenes)) {
        Scene scene = sceneNamed(name, o.scenesDir);
        for (auto [width, height] : lists.resolutions) {
            for (std::uint32_t n : lists.photons) {
                RenderSettings s = scene.render;
                chooseEstimator(s, lists);
                s.width = width;
                s.height = height;
                s.photons = n;
                cases.emplace_back(scene, PhotonUseCase{name, s});
            }
        }
    }
    benchPhotonUse(*backend, cases, o.photonUse);
}

// The scenes of the source tree the program was built from, or where it is installed the ones
// installed beside it (share/photon/scenes), or the source tree's again (for the message).
std::string defaultScenesDir() {
    std::error_code error;
    if (std::filesystem::is_directory(PHOTON_SCENES_DIR, error)) {
        return PHOTON_SCENES_DIR;
    }
    std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    std::filesystem::path installed = self.parent_path() / PHOTON_INSTALLED_SCENES;
    return !error && std::filesystem::is_directory(installed, error) ? installed.lexically_normal().string() : PHOTON_SCENES_DIR;
}

int run(int argc, char** argv) {
    CLI::App app{"Photon benchmark: per-stage times over scenes, resolutions, photon counts and backends",
                 "photon-bench"};
    BenchOptions o;
    o.scenesDir = defaultScenesDir();
    addOptions(app, o);
    if (int code = parseCommandLine(app, argc, argv); code >= 0) {
        return code;
    }
    CaseLists lists = parseLists(app, o);
    if (!o.jsonPath.empty()) {
        checkOutputPath(o.jsonPath, "JSON table");
    }
    if (!o.csvPath.empty()) {
        checkOutputPath(o.csvPath, "CSV table");
    }
    if (o.imageWriters) {
        runImageWriters(o, lists);
    } else if (o.photonUse > 0) {
        runPhotonUse(o, lists);
    } else if (o.bvhBuilds > 0) {
        benchBvhBuilds(splitList(o.scenes), o.scenesDir, o.bvhBuilds, parseThreadCounts(o.threads), o.jsonPath);
    } else {
        benchFrameTimes(o, lists, kProcessStart);
    }
    return 0;
}

}  // namespace
}  // namespace photon

int main(int argc, char** argv) {
    return photon::runProgram("photon-bench", [&] { return photon::run(argc, argv); });
}
