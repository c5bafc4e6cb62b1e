// The render settings on the command line, shared by photon-render and photon-view: one option
// per setting of core/settings/setting_specs.h, parsed and checked there. Only the options given
// on the command line override the scene file's settings.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/loaders/model_loader.h"
#include "core/scene/scene.h"
#include "core/settings/settings.h"

namespace photon {

struct RenderOptions {
    std::map<std::string, std::string> values;  // flag → text as given
    std::map<std::string, bool> flags;          // flag → given (settings without a value)
    // --allow-outside-paths: not a render setting (a scene file cannot give it to itself), but how
    // model files are read.
    PathPolicy paths;
    // --environment FILE and --environment-intensity X: an environment map that lights any scene.
    std::string environment;
    std::string environmentIntensity;
};

// The items of a comma-separated option ("cuda,vulkan"), empty ones dropped.
std::vector<std::string> splitList(const std::string& text);

// `text` read as an unsigned number by std::stoul, which must take every character; false if it
// takes none or not all. (stoul accepts leading white space and wraps a leading '-', so callers
// that mind check for them.)
bool parseWholeNumber(const std::string& text, unsigned long& value);

// The settings' options, and --allow-outside-paths.
void addRenderOptions(CLI::App& app, RenderOptions& options);

// Replaces the scene's environment (or background) with --environment's map, lighting it, and
// finalizes the scene again; nothing if the option was not given. Throws InputError naming the
// option and the file.
void applyEnvironmentOption(const CLI::App& app, const RenderOptions& options, Scene& scene);

// Applies the options that were given; throws InputError "--flag: reason" for a bad value.
void applyRenderOptions(const CLI::App& app, const RenderOptions& options, RenderSettings& settings);

// Sets one setting by its scene-file name ("cell_size", "estimator", ...), for photon-bench's
// --vary. Throws InputError for an unknown name or a bad value.
void applySetting(RenderSettings& settings, const std::string& key, const std::string& value);

}  // namespace photon
