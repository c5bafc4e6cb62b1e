// photon-converge: error against time. Renders a scene frame after frame with each estimator and,
// at every checkpoint (1, 2, 4, ... frames, or --times milliseconds), compares the image with a
// converged reference (core/image/image_error.h): relative RMSE of the whole image, away from the
// focus (outside the reference's brightest 0.5%) and at its edges, the focus's energy and peak
// relative to the reference's, SSIM of the display images; and in the caustic window the peak and
// energy. With the denoiser on (--set denoise=on) each checkpoint is measured without and with it,
// the denoised one at its time plus the denoise stage's. Time is the backend's own GPU (or CPU)
// stage time, summed over the frames; reading the image back for the comparison is not counted.
//
//   photon-render scenes/smallpt.json --backend cuda --estimator sppm --frames 4096 --photons 4000000 -o ref.pfm
//   photon-converge scenes/smallpt.json --reference ref.pfm --backend cuda --estimators sppm,progressive,radius
//                   --photons 1000000 --frames 1024 --json smallpt-error.json
//   photon-converge --compare image.pfm --reference ref.pfm     (one image: its error)
//   photon-converge scenes/cornell.json --camera-path orbit:20 --backend cuda  (a moving view: apps/orbit_error.h)
#include <algorithm>
#include <cstdio>
#include <functional>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/frame/glass_pixels.h"
#include "core/frame/scene_settings.h"
#include "core/render/devices.h"
#include "apps/orbit_error.h"
#include "apps/render_options.h"
#include "core/image/image_error.h"
#include "core/loaders/scene_loader.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "core/system/output_file.h"
#include "core/system/program.h"

namespace photon {
namespace {

// A whole number in [0, limit], or InputError naming the option.
std::uint32_t parseCount(const std::string& text, std::uint32_t limit, const std::string& what) {
    unsigned long v = 0;
    if (!parseWholeNumber(text, v) || text[0] == '-' || v > limit) {
        throw InputError(what + ": '" + text + "' is not a whole number in [0, " + std::to_string(limit) + "]");
    }
    return std::uint32_t(v);
}

// "auto" (the 7 × 7 pixels about the reference's brightest), "auto:H" ((2H + 1)²), or x0,y0,x1,y1.
Window parseWindow(const std::string& text, const Image& reference) {
    if (text == "auto" || text.rfind("auto:", 0) == 0) {
        std::uint32_t half = text.size() > 5 ? parseCount(text.substr(5), 1024, "--window") : 3u;
        return brightestWindow(reference, half);
    }
    std::vector<std::string> parts = splitList(text);
    Window w;
    if (parts.size() == 4) {
        w.x0 = parseCount(parts[0], reference.width, "--window");
        w.y0 = parseCount(parts[1], reference.height, "--window");
        w.x1 = parseCount(parts[2], reference.width, "--window");
        w.y1 = parseCount(parts[3], reference.height, "--window");
    }
    if (parts.size() != 4 || w.empty()) {
        throw InputError("--window: '" + text + "' is not x0,y0,x1,y1 within the " + std::to_string(reference.width) +
                         "x" + std::to_string(reference.height) + " reference, nor auto[:H]");
    }
    return w;
}

void printHeading() {
    std::printf("%-34s %10s %9s %9s %8s %8s %9s %9s %8s %8s %7s %8s %7s %8s %7s\n", "estimator, frames", "time ms",
                "rmse", "outside", "peak", "energy", "away", "edges", "focus E", "focus pk", "ssim", "glass", "off25",
                "rest", "off25");
}

void printError(const std::string& label, double ms, const ImageError& e, const Quality& q) {
    std::printf("%-34s %10.2f %9.4f %9.4f %8.3f %8.3f %9.4f %9.4f %8.3f %8.3f %7.4f %8.4f %7.4f %8.4f %7.4f\n",
                label.c_str(), ms, e.whole, e.outside, e.peakRatio, e.energyRatio, q.away, q.edges, q.focusEnergy,
                q.focusPeak, q.ssim, q.glass, q.glassOff, q.rest, q.restOff);
    std::fflush(stdout);
}

// The glass region's columns: the pixels whose camera ray first meets glass (core/frame/glass_pixels.h),
// and the rest of the image away from the focus; each a relative RMSE and the share off by > 25%.
nlohmann::json errorJson(const ImageError& e, const Quality& q) {
    return {{"rmse", e.whole},           {"rmse_outside_window", e.outside}, {"peak_ratio", e.peakRatio},
            {"energy_ratio", e.energyRatio}, {"rmse_away_from_focus", q.away},  {"rmse_edges", q.edges},
            {"focus_energy_ratio", q.focusEnergy}, {"focus_peak_ratio", q.focusPeak}, {"ssim", q.ssim},
            {"rmse_glass", q.glass}, {"glass_off_25", q.glassOff}, {"rmse_rest_away", q.rest},
            {"rest_off_25", q.restOff}};
}

// --set KEY=VALUE ...
void applyOverrides(RenderSettings& settings, const std::vector<std::string>& overrides) {
    for (const std::string& o : overrides) {
        std::size_t eq = o.find('=');
        const SettingSpec* spec = eq == std::string::npos ? nullptr : findSetting(o.substr(0, eq));
        if (spec == nullptr) {
            throw InputError("--set " + o + ": expected KEY=VALUE with a render setting's key");
        }
        setSetting(settings, *spec, o.substr(eq + 1), "--set " + o.substr(0, eq));
    }
}

// The checkpoints of --times: milliseconds, ascending.
std::vector<double> parseTimes(const std::string& text) {
    std::vector<double> times;
    double last = 0.0;
    for (const std::string& item : splitList(text)) {
        double t = parseNumber(item, Range{0.0, 1e9, true, false}, "--times");
        if (t <= last) {
            throw InputError("--times: '" + text + "' is not ascending");
        }
        times.push_back(t);
        last = t;
    }
    return times;
}

// What the command line gives.
struct ConvergeOptions {
    std::string scenePath;
    std::string referencePath;
    std::string comparePath;
    std::string backendName = "auto";
    std::string estimators = "sppm,progressive,radius";
    std::string windowText = "auto";
    std::string jsonPath;
    std::string timesText;
    std::string imagesDir;
    std::uint32_t maxFrames = 256;
    DeviceOptions options;
    std::vector<std::string> overrides;
    std::string cameraPath;
    OrbitMeasurement orbit;
    bool flicker = false;
};

void addOptions(CLI::App& app, ConvergeOptions& o) {
    app.add_option("scene", o.scenePath, "Scene file (its render settings, then the options below)")->check(kFileName);
    app.add_option("--reference", o.referencePath, "The converged image (.pfm or .exr); not with --camera-path")->check(kFileName);
    app.add_option("--compare", o.comparePath, "Only compare this image (.pfm or .exr) with the reference")->check(kFileName);
    app.add_option("--backend", o.backendName, "auto|cpu|cuda|vulkan, or a list (one device each)")->check(kBackendList);
    app.add_option("--device", o.options.device, "GPU to use: index or part of its name");
    app.add_option("--estimators", o.estimators, "Comma-separated estimators to measure");
    app.add_option("--frames", o.maxFrames, "Frames of each estimator; checkpoints at 1, 2, 4, ... and this")
        ->check(CLI::Range(1u, 1000000u));
    app.add_option("--window", o.windowText, "The caustic window: auto[:H] about the reference's brightest pixel, or x0,y0,x1,y1");
    app.add_option("--set", o.overrides, "KEY=VALUE: a render setting of the scene file (photons, width, seed, ...)");
    app.add_option("--json", o.jsonPath, "Write the measurements as JSON")->check(kFileName);
    app.add_option("--times", o.timesText,
                   "Checkpoints in milliseconds of stage time, e.g. 16,33,100,400 (in place of frames 1, 2, 4, ...; "
                   "--frames still caps the frames)");
    app.add_flag("--flicker", o.flicker,
                 "With the denoiser: one frame more after each checkpoint, and how much the image shown changes "
                 "(a still camera's flicker)");
    app.add_option("--images", o.imagesDir, "Write each checkpoint's images as PFM into this folder")->check(kFileName);
    app.add_option("--camera-path", o.cameraPath,
                   "orbit:SECONDS: the error while the camera moves, restarting and reprojecting, against references "
                   "rendered at sample frames' cameras (no --reference)");
    app.add_option("--path-frames", o.orbit.frames, "--camera-path: frames along it, 1/60 s apart")->check(CLI::Range(2u, 100000u));
    app.add_option("--samples", o.orbit.samples, "--camera-path: frames compared, evenly spread")->check(CLI::Range(1u, 1000u));
    app.add_option("--reference-frames", o.orbit.referenceFrames, "--camera-path: frames of each sample's reference")
        ->check(CLI::Range(1u, 1000000u));
}

// --scene, and its settings with the command line's overrides. A --json file's path is checked
// first, so that a bad one fails before the scene is loaded and rendered.
Scene loadScene(const ConvergeOptions& o, RenderSettings& settings) {
    if (!o.jsonPath.empty()) {
        checkOutputPath(o.jsonPath, "JSON");
    }
    Scene scene = loadSceneFile(o.scenePath);
    settings = scene.render;
    applyOverrides(settings, o.overrides);
    return scene;
}

// Writes the measurements to --json, if given.
void writeJson(const ConvergeOptions& o, const nlohmann::json& out) {
    if (!o.jsonPath.empty()) {
        writeOutputFile(o.jsonPath, out.dump(2) + "\n", "JSON");
    }
}

// --camera-path: the error while the camera moves (apps/orbit_error.h).
void runOrbit(const ConvergeOptions& o) {
    OrbitMeasurement orbit = o.orbit;
    orbit.path = parseCameraPath(o.cameraPath, "--camera-path");
    orbit.imagesDir = o.imagesDir;
    if (!o.referencePath.empty() || !o.comparePath.empty() || o.scenePath.empty()) {
        throw InputError("--camera-path: give a scene and no --reference or --compare (it renders its own references)");
    }
    RenderSettings s;
    Scene scene = loadScene(o, s);
    chooseDefaults(s, true);
    chooseInteractive(s);
    chooseSpectral(s, scene);
    auto make = [&] { return createRenderer(o.backendName, o.options); };
    choosePhotons(s, make()->runsOnCpu());
    validateSettings(s);
    nlohmann::json out = measureOrbit(make, scene, s, orbit);
    out["scene"] = scene.name;
    out["photons_per_frame"] = s.photons;
    writeJson(o, out);
}

// An image's error against the reference, and its quality measures.
using Measure = std::function<std::pair<ImageError, Quality>(const Image&)>;

// Renders up to --frames frames with `s` on `backend` and measures the image (and the denoised
// one, with the denoiser on) at every checkpoint; returns the checkpoints' rows.
nlohmann::json measureCheckpoints(Renderer& backend, const RenderSettings& s, const std::string& name,
                                  const ConvergeOptions& o, const std::vector<double>& times, const Measure& measure) {
    double ms = 0.0;
    std::uint32_t next = 1;
    std::size_t nextTime = 0;
    nlohmann::json rows = nlohmann::json::array();
    for (std::uint32_t f = 1; f <= o.maxFrames; ++f) {
        backend.renderFrame();
        ms += backend.lastFrameStats().ms.total();
        bool checkpoint = times.empty() ? f == next || f == o.maxFrames : ms >= times[nextTime] || f == o.maxFrames;
        if (!checkpoint) {
            continue;
        }
        std::string label = name + ", " + std::to_string(f);
        Image raw = backend.rawImage();
        auto [e, q] = measure(raw);
        printError(label, ms, e, q);
        nlohmann::json row = errorJson(e, q);
        row["frames"] = f;
        row["ms"] = ms;
        if (!o.imagesDir.empty()) {
            writeImage(o.imagesDir + "/" + name + "-" + std::to_string(f) + ".pfm", raw, 0.0f, Tonemap::Clamp);
        }
        if (denoises(s)) {
            Image denoised = backend.image();
            double denoiseMs = backend.lastFrameStats().ms[STAGE_DENOISE];
            auto [de, dq] = measure(denoised);
            printError(label + " denoised", ms + denoiseMs, de, dq);
            row["denoised"] = errorJson(de, dq);
            row["denoise_ms"] = denoiseMs;
            if (!o.imagesDir.empty()) {
                writeImage(o.imagesDir + "/" + name + "-" + std::to_string(f) + "-denoised.pfm", denoised, 0.0f,
                           Tonemap::Clamp);
            }
            if (o.flicker && f < o.maxFrames) {
                // The next frame, as a still viewer shows it: how much its pixels change.
                backend.renderFrame();
                ms += backend.lastFrameStats().ms.total();
                ++f;
                double change = meanChange(backend.image(), denoised);
                std::printf("%-34s flicker %.4f%% (frame %u against %u)\n", label.c_str(), 100.0 * change, f, f - 1);
                row["flicker"] = change;
            }
        }
        rows.push_back(row);
        next *= 2;
        while (nextTime < times.size() && ms >= times[nextTime]) {
            ++nextTime;  // a frame longer than the gap between checkpoints passes several
        }
        if (!times.empty() && nextTime == times.size()) {
            break;
        }
    }
    return rows;
}

int run(int argc, char** argv) {
    CLI::App app{"Error against time: each estimator's image against a converged reference", "photon-converge"};
    ConvergeOptions o;
    addOptions(app, o);
    if (int code = parseCommandLine(app, argc, argv); code >= 0) {
        return code;
    }
    if (!o.cameraPath.empty()) {
        runOrbit(o);
        return 0;
    }
    if (o.referencePath.empty()) {
        throw InputError("--reference is required (or --camera-path)");
    }
    Image reference = readImage(o.referencePath);
    Window window = parseWindow(o.windowText, reference);
    std::vector<double> times = parseTimes(o.timesText);
    std::printf("reference %s: %ux%u, window [%u, %u) x [%u, %u)\n", o.referencePath.c_str(), reference.width,
                reference.height, window.x0, window.x1, window.y0, window.y1);
    if (o.scenePath.empty() && o.comparePath.empty()) {
        throw InputError("a scene is needed (or --compare IMAGE)");
    }
    // With a scene (also beside --compare), its glass region is measured apart.
    RenderSettings base;
    Scene scene;
    PixelMask glass;
    if (!o.scenePath.empty()) {
        scene = loadScene(o, base);
        if (base.width != reference.width || base.height != reference.height) {
            throw InputError("--reference: " + o.referencePath + " is " + std::to_string(reference.width) + "x" +
                             std::to_string(reference.height) + ", the render " + std::to_string(base.width) + "x" +
                             std::to_string(base.height));
        }
        glass = glassPixels(scene, scene.camera, base);
        std::size_t count = std::size_t(std::count(glass.begin(), glass.end(), true));
        std::printf("glass region: %zu pixels (%.1f%%) whose camera ray first meets glass\n", count,
                    100.0 * double(count) / double(glass.size()));
    }
    QualityMasks masks(reference, glass);
    printHeading();
    Measure measure = [&](const Image& image) {
        return std::pair{compareWithReference(image, reference, window), measureQuality(image, reference, masks)};
    };
    if (!o.comparePath.empty()) {
        auto [e, q] = measure(readImage(o.comparePath));
        printError(o.comparePath, 0.0, e, q);
        return 0;
    }
    std::unique_ptr<Renderer> backend = createRenderer(o.backendName, o.options);
    choosePhotons(base, backend->runsOnCpu());
    chooseSpectral(base, scene);
    backend->setScene(scene);
    nlohmann::json out;
    out["scene"] = scene.name;
    out["backend"] = backend->name();
    out["device"] = backend->deviceName();
    out["photons_per_frame"] = base.photons;
    out["window"] = {window.x0, window.y0, window.x1, window.y1};
    for (const std::string& name : splitList(o.estimators)) {
        RenderSettings s = base;
        setSetting(s, *findSetting("estimator"), name, "--estimators");
        backend->setSettings(s);
        out["estimators"][name] = measureCheckpoints(*backend, s, name, o, times, measure);
    }
    writeJson(o, out);
    return 0;
}

}  // namespace
}  // namespace photon

int main(int argc, char** argv) {
    return photon::runProgram("photon-converge", [&] { return photon::run(argc, argv); });
}
