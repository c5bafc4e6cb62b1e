// Command-line options that override a scene's render settings, shared by photon-render and
// photon-view. Only the options given on the command line override the scene file.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "core/settings.h"

namespace photon {

struct RenderOptions {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint32_t photons = 0;
    std::uint32_t frames = 0;
    std::string estimator;
    std::string kernel;
    float radius = 0.0f;
    float causticRadius = 0.0f;
    std::uint32_t k = 0;
    float alpha = 0.0f;
    std::uint32_t seed = 0;
    bool pixelCenter = false;
    std::string global;
    std::uint32_t gatherRays = 0;
    std::uint32_t lightSamples = 0;
    std::uint32_t maxEyeDepth = 0;
    std::uint32_t maxPhotonDepth = 0;
    float causticFraction = 0.0f;
    std::string grid;
    std::uint32_t gridResolution = 0;
    float cellSize = 0.0f;
    std::uint32_t gatherBudget = 0;
    std::string view;
    float exposure = 0.0f;
    std::string tonemap;
};

void addRenderOptions(CLI::App& app, RenderOptions& options);

// Applies the options that were given; throws InputError for a bad enumeration value.
void applyRenderOptions(const CLI::App& app, const RenderOptions& options, RenderSettings& settings);

// Sets one setting by its scene-file name ("cell_size", "gather_budget", "estimator", ...), for
// photon-bench's --vary. Throws InputError for an unknown name or value.
void applySetting(RenderSettings& settings, const std::string& key, const std::string& value);

}  // namespace photon
