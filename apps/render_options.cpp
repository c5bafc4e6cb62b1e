#include "render_options.h"

#include "core/error.h"
#include "shared/constants.h"

namespace photon {
namespace {

template <typename E>
void applyEnum(const CLI::App& app, const char* flag, const std::string& value, E& out) {
    if (app.count(flag) == 0) {
        return;
    }
    if (!parse(value, out)) {
        throw InputError(std::string(flag) + ": unknown value '" + value + "' (expected " + choices(out) + ")");
    }
}

template <typename T>
void applyValue(const CLI::App& app, const char* flag, const T& value, T& out) {
    if (app.count(flag) > 0) {
        out = value;
    }
}

}  // namespace

void addRenderOptions(CLI::App& app, RenderOptions& o) {
    auto positive = CLI::PositiveNumber;
    app.add_option("--width", o.width, "Image width in pixels")->check(CLI::Range(1u, 16384u));
    app.add_option("--height", o.height, "Image height in pixels")->check(CLI::Range(1u, 16384u));
    app.add_option("--photons", o.photons, "Photon paths emitted per frame (both passes)")->check(CLI::Range(1u, 1u << 28));
    app.add_option("--frames", o.frames, "Frames averaged into the image")->check(CLI::Range(1u, 1000000u));
    app.add_option("--estimator", o.estimator, "Radiance estimate: " + choices(Estimator{}));
    app.add_option("--kernel", o.kernel, "Density kernel: " + choices(Kernel{}));
    app.add_option("--radius", o.radius, "Global map query radius (scene units)")->check(positive);
    app.add_option("--caustic-radius", o.causticRadius, "Caustic map query radius")->check(positive);
    app.add_option("--k", o.k, "Photons of the k-nearest estimator")->check(CLI::Range(1u, KNN_MAX));
    app.add_option("--alpha", o.alpha, "Progressive radius reduction α")->check(CLI::Range(0.01f, 0.99f));
    app.add_option("--seed", o.seed, "Random seed");
    app.add_flag("--pixel-center", o.pixelCenter, "One ray through each pixel centre: no jitter, no depth of field");
    app.add_option("--global", o.global, "Indirect light from the global map: " + choices(GlobalMode{}));
    app.add_option("--gather-rays", o.gatherRays, "Final-gather rays per pixel")->check(CLI::Range(1u, 1024u));
    app.add_option("--light-samples", o.lightSamples, "Shadow rays per light")->check(CLI::Range(1u, 1024u));
    app.add_option("--max-depth", o.maxEyeDepth, "Specular bounces of an eye path")->check(CLI::Range(1u, 64u));
    app.add_option("--max-photon-depth", o.maxPhotonDepth, "Surfaces a photon may hit")->check(CLI::Range(1u, 64u));
    app.add_option("--caustic-fraction", o.causticFraction, "Share of photons aimed at specular objects")
        ->check(CLI::Range(0.0f, 0.99f));
    app.add_option("--grid", o.grid, "Photon map grid: " + choices(GridKind{}));
    app.add_option("--grid-resolution", o.gridResolution, "k of the bounded k³ grid")->check(CLI::Range(1u, 1024u));
    app.add_option("--cell-size", o.cellSize, "Hashed grid cell edge in query radii (≥ 1)")->check(CLI::Range(1.0f, 64.0f));
    app.add_option("--gather-budget", o.gatherBudget, "Photons a query visits per cell before subsampling it (0: all)");
    app.add_option("--view", o.view, "What to show: " + choices(View{}));
    app.add_option("--exposure", o.exposure, "Exposure in stops (PNG and display)");
    app.add_option("--tonemap", o.tonemap, "Tone curve: " + choices(Tonemap{}));
}

void applyRenderOptions(const CLI::App& app, const RenderOptions& o, RenderSettings& s) {
    applyValue(app, "--width", o.width, s.width);
    applyValue(app, "--height", o.height, s.height);
    applyValue(app, "--photons", o.photons, s.photons);
    applyValue(app, "--frames", o.frames, s.frames);
    applyEnum(app, "--estimator", o.estimator, s.estimator);
    applyEnum(app, "--kernel", o.kernel, s.kernel);
    applyValue(app, "--radius", o.radius, s.radius);
    applyValue(app, "--caustic-radius", o.causticRadius, s.causticRadius);
    applyValue(app, "--k", o.k, s.k);
    applyValue(app, "--alpha", o.alpha, s.alpha);
    applyValue(app, "--seed", o.seed, s.seed);
    if (o.pixelCenter) {
        s.pixelCenter = true;
    }
    applyEnum(app, "--global", o.global, s.globalMode);
    applyValue(app, "--gather-rays", o.gatherRays, s.gatherRays);
    applyValue(app, "--light-samples", o.lightSamples, s.lightSamples);
    applyValue(app, "--max-depth", o.maxEyeDepth, s.maxEyeDepth);
    applyValue(app, "--max-photon-depth", o.maxPhotonDepth, s.maxPhotonDepth);
    applyValue(app, "--caustic-fraction", o.causticFraction, s.causticFraction);
    applyEnum(app, "--grid", o.grid, s.grid);
    applyValue(app, "--grid-resolution", o.gridResolution, s.gridResolution);
    applyValue(app, "--cell-size", o.cellSize, s.cellSize);
    applyValue(app, "--gather-budget", o.gatherBudget, s.gatherBudget);
    applyEnum(app, "--view", o.view, s.view);
    applyValue(app, "--exposure", o.exposure, s.exposure);
    applyEnum(app, "--tonemap", o.tonemap, s.tonemap);
}

void applySetting(RenderSettings& s, const std::string& key, const std::string& value) {
    auto number = [&] {
        try {
            return std::stod(value);
        } catch (const std::exception&) {
            throw InputError(key + "=" + value + ": not a number");
        }
    };
    auto enumeration = [&](auto& out) {
        if (!parse(value, out)) {
            throw InputError(key + "=" + value + ": expected " + choices(out));
        }
    };
    if (key == "cell_size") {
        s.cellSize = float(number());
    } else if (key == "gather_budget") {
        s.gatherBudget = std::uint32_t(number());
    } else if (key == "radius") {
        s.radius = float(number());
    } else if (key == "caustic_radius") {
        s.causticRadius = float(number());
    } else if (key == "caustic_fraction") {
        s.causticFraction = float(number());
    } else if (key == "k") {
        s.k = std::uint32_t(number());
    } else if (key == "estimator") {
        enumeration(s.estimator);
    } else if (key == "kernel") {
        enumeration(s.kernel);
    } else if (key == "grid") {
        enumeration(s.grid);
    } else if (key == "global") {
        enumeration(s.globalMode);
    } else if (key == "view") {
        enumeration(s.view);
    } else {
        throw InputError("unknown setting '" + key + "'");
    }
}

}  // namespace photon
