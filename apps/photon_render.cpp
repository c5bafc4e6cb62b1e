// photon-render: renders a scene file (or the built-in Cornell box) to an image, headless.
//
//   photon-render [scene.json] --backend auto|cpu|cuda|vulkan --width W --height H --photons N
//                 --frames F | --time SECONDS --estimator ... --output FILE --stats FILE
//
// Exit codes: 0 success, 2 bad input (scene, options), 1 runtime failure (e.g. no such backend),
// 128 + the signal after SIGINT or SIGTERM (130 for Ctrl-C): the first finishes the frame in
// flight and writes the image so far, a second ends the process at once (apps/interrupt.h).
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/frame/scene_settings.h"
#include "core/render/render.h"
#include "apps/interrupt.h"
#include "apps/progress.h"
#include "apps/render_options.h"
#include "core/render/render_stats.h"
#include "core/frame/median.h"
#include "core/loaders/scene_loader.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "core/system/output_file.h"
#include "core/frame/aov_images.h"
#include "core/system/program.h"

namespace photon {
namespace {

nlohmann::json stageJson(const std::vector<StageTimes>& frames) {
    nlohmann::json stages;
    for (const StageInfo& stage : kStages) {
        std::vector<double> v;
        double sum = 0.0;
        for (const StageTimes& t : frames) {
            v.push_back(t[stage.id]);
            sum += t[stage.id];
        }
        stages[stage.name] = {{"median_ms", median(v)}, {"total_ms", sum}};
    }
    std::vector<double> totals;
    for (const StageTimes& t : frames) {
        totals.push_back(t.total());
    }
    stages["frame"] = {{"median_ms", median(totals)}};
    return stages;
}

// Where the render goes, and what it says on the way.
struct Outputs {
    std::string image;          // --output
    std::string stats;          // --stats; empty: none
    std::string source;         // the scene as messages name it
    bool quiet = false;         // --quiet
};

// A warning on stderr, unless --quiet.
void warn(const Outputs& out, const std::string& warning) {
    if (!out.quiet) {
        std::fprintf(stderr, "%s\n", printable(warning).c_str());
    }
}

// Writes the image (and the stats) of a finished or interrupted render and says how it went;
// returns the exit code.
int writeResult(const RenderResult& result, const RenderSettings& settings, const Outputs& out,
                std::vector<std::string> warnings, nlohmann::json stats) {
    const std::string& output = out.image;
    const std::string& statsPath = out.stats;
    // Interrupted (here, or in another process of an MPI render: the signal it got): what was
    // rendered is written as it would have been at the end.
    int interrupted = result.cancelled;
    const Image& image = result.image;
    std::uint32_t frames = static_cast<std::uint32_t>(result.times.size());
    double wall = result.seconds;
    // An EXR file gets the image without the denoiser beside the denoised one, and the AOVs.
    std::vector<ExrLayer> layers;
    if (!result.raw.pixels.empty()) {
        layers.push_back({"raw", &result.raw, "RGB"});
    }
    if (settings.aov) {
        for (const ExrLayer& layer : exrLayers(result.aovs)) {
            layers.push_back(layer);
        }
    }
    // A black image with exit 0 looks like a bug; say so, with the likely reasons.
    if (std::string black = nearlyBlackWarning(image, settings.exposure, out.source); !black.empty() && interrupted == 0) {
        warnings.push_back(black);
        warn(out, warnings.back());
    }
    writeImage(output, image, settings.exposure, settings.tonemap, layers);
    if (!statsPath.empty()) {
        stats["frames"] = frames;
        stats["wall_seconds"] = wall;
        stats["stages"] = stageJson(result.times);
        stats["warnings"] = warnings;
        writeOutputFile(statsPath, stats.dump(2) + "\n", "stats");
    }
    if (interrupted != 0) {
        std::fprintf(stderr, "photon-render: %s%s: stopped after %u frame%s; the image so far is in %s%s%s\n",
                     interrupted == SIGINT ? "interrupted" : "terminated",
                     interruptSignal() == 0 ? " (in another process)" : "", frames, frames == 1 ? "" : "s",
                     printable(output).c_str(), statsPath.empty() ? "" : ", the stats in ", printable(statsPath).c_str());
        return 128 + interrupted;
    }
    if (!out.quiet) {
        std::string processes = result.processes > 1 ? " in each of " + std::to_string(result.processes) + " processes" : "";
        std::fprintf(stderr, "%s on %s%s: %ux%u, %u frame%s in %.2f s (%.1f ms/frame), photons stored %s -> %s\n",
                     result.backend.c_str(), result.device.c_str(), processes.c_str(), settings.width, settings.height, frames,
                     frames == 1 ? "" : "s", wall, 1000.0 * wall / frames, result.last.storedList().c_str(), output.c_str());
    }
    return 0;
}

int run(int argc, char** argv) {
    installInterruptHandlers();
    CLI::App app{"Photon: renders a scene with photon mapping", "photon-render"};
    std::string scenePath;
    std::string backendName = "auto";
    std::string output = "render.png";
    std::string statsPath;
    DeviceOptions backendOptions;
    bool quiet = false;
    double seconds = 0.0;
    RenderOptions options;
    app.add_option("scene", scenePath, "Scene file (JSON) or model (.obj, .gltf, .glb); the built-in Cornell box if omitted")->check(kFileName);
    app.add_option("--backend", backendName,
                   "auto|cpu|cuda|vulkan (auto: a GPU if there is one, else the CPU); a list renders on several "
                   "devices, one each (cpu,cpu or cuda,cuda)")
        ->check(kBackendList);
    app.add_option("--device", backendOptions.device,
                   "GPU to use: index or part of its name; one per backend of a list (0,1)");
    addSwitch(app, "--validation", backendOptions.validation, "Vulkan: validation layer on; any message fails");
    app.add_option("--output,-o", output, "Image file: .png (tone-mapped), .exr or .pfm (linear)")->check(kFileName);
    app.add_option("--stats", statsPath, "Write per-stage times and photon counts as JSON")->check(kFileName);
    std::string secondsText;
    const Range kSeconds{0.001, 1e6};
    app.add_option("--time", secondsText,
                   "Render frames until this many seconds have passed (at most --frames if given; " +
                       kSeconds.describe() + ")");
    addSwitch(app, "--quiet,-q", quiet, "Print nothing but errors");
    addRenderOptions(app, options);
    if (int code = parseCommandLine(app, argc, argv); code >= 0) {
        return code;
    }
    if (app.count("--time") > 0) {
        seconds = parseNumber(secondsText, kSeconds, "--time");
    }

    Scene scene = app.count("scene") == 0 ? defaultScene() : loadSceneFile(scenePath, options.paths);
    applyEnvironmentOption(app, options, scene);
    RenderSettings settings = scene.render;
    applyRenderOptions(app, options, settings);
    // No length given anywhere: as long as a clean image takes on a small machine's CPU.
    bool timed = app.count("--time") > 0;
    bool framesGiven = isGiven(settings, "frames");
    if (!timed && !framesGiven) {
        timed = true;
        seconds = kDefaultRenderSeconds;
    }
    chooseDefaults(settings, timed);
    chooseSpectral(settings, scene);
    validateSettings(settings);
    // Outputs that cannot be written fail now, not after the render.
    ImageFormat format = imageFormatFor(output);
    checkOutputPath(output, "image");
    if (!statsPath.empty()) {
        checkOutputPath(statsPath, "stats");
    }

    // Named by the file: a scene file's "name" may be empty, or say nothing of where it came from.
    std::string source = app.count("scene") == 0 ? "<embedded cornell.json>" : scenePath;
    // Under mpirun every process renders its share; the first prints and writes.
    Outputs out{output, statsPath, source, quiet || launchedRank() != 0};
    std::vector<std::string> warnings = scene.warnings;
    if (settings.aov && format != ImageFormat::Exr) {
        warnings.push_back(output + ": only an .exr file holds the auxiliary images (--aov); this one gets the image alone");
    }
    for (const std::string& warning : warnings) {
        warn(out, warning);
    }
    RenderJob job;
    job.backend = backendName;
    job.device = backendOptions;
    job.seconds = timed ? seconds : 0.0;
    job.framesCap = framesGiven;
    ProgressBar progress(timed ? 0 : settings.frames, timed ? seconds : 0.0, !out.quiet);
    nlohmann::json stats;
    RenderObserver observer;
    observer.frame = [&](std::uint32_t frames, double elapsed) { progress.update(frames, elapsed); };
    observer.cancel = [] { return interruptSignal(); };
    observer.finished = [&](Renderer& backend) {
        progress.finish();
        if (!statsPath.empty()) {
            stats = renderStatsJson(backend);
        }
    };
    RenderResult result = render(std::move(scene), settings, job, observer);
    if (!result.leader) {
        return result.cancelled != 0 ? 128 + result.cancelled : 0;
    }
    return writeResult(result, settings, out, warnings, std::move(stats));
}

}  // namespace
}  // namespace photon

int main(int argc, char** argv) {
    return photon::runProgram("photon-render", [&] { return photon::run(argc, argv); });
}
