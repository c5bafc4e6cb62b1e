#include "render_options.h"

#include <sstream>
#include <stdexcept>

#include "core/loaders/environment_loader.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "core/system/program.h"

namespace photon {

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        if (!item.empty()) {
            out.push_back(item);
        }
    }
    return out;
}

bool parseWholeNumber(const std::string& text, unsigned long& value) {
    std::size_t used = 0;
    try {
        value = std::stoul(text, &used);
    } catch (const std::exception&) {
        return false;
    }
    return used != 0 && used == text.size();
}

void addRenderOptions(CLI::App& app, RenderOptions& o) {
    for (const SettingSpec& spec : settingSpecs()) {
        std::string help = spec.help;
        if (spec.kind == SettingKind::Flag) {
            // Each flag also has its --no- form, to turn off what a scene file turned on.
            addSwitch(app, spec.flag, o.flags[spec.flag], help);
            continue;
        }
        // Given twice, the last one counts (as in most tools), so that a script can override.
        if (spec.kind == SettingKind::Choice) {
            help += ": " + spec.choices;
        } else {
            help += " (" + (spec.kind == SettingKind::Integer ? std::string("integer ") : std::string()) +
                    spec.range.describe() + ")";
        }
        app.add_option(spec.flag, o.values[spec.flag], help)->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    }
    addSwitch(app, "--allow-outside-paths", o.paths.allowOutside,
                 "Let model files read buffers, images, MTL files and textures outside their own folder");
    app.add_option("--environment", o.environment,
                   "Light the scene with this equirectangular .hdr or .exr map (replaces its environment or background)")
        ->check(kFileName);
    app.add_option("--environment-intensity", o.environmentIntensity,
                   "Factor on the --environment map's texels (" + kEnvironmentIntensity.describe() + ")");
}

void applyEnvironmentOption(const CLI::App& app, const RenderOptions& o, Scene& scene) {
    if (app.count("--environment-intensity") > 0 && app.count("--environment") == 0) {
        throw InputError("--environment-intensity: only with --environment");
    }
    if (app.count("--environment") == 0) {
        return;
    }
    float intensity = app.count("--environment-intensity") > 0
                          ? parseNumber(o.environmentIntensity, kEnvironmentIntensity, "--environment-intensity")
                          : 1.0f;
    lightWithEnvironmentMap(scene, o.environment, intensity, "--environment");
}

void applyRenderOptions(const CLI::App& app, const RenderOptions& o, RenderSettings& settings) {
    for (const SettingSpec& spec : settingSpecs()) {
        if (app.count(spec.flag) == 0) {
            continue;
        }
        if (spec.kind == SettingKind::Flag) {
            setSetting(settings, spec, o.flags.at(spec.flag) ? "true" : "false", spec.flag);
        } else {
            setSetting(settings, spec, o.values.at(spec.flag), spec.flag);
        }
    }
}

void applySetting(RenderSettings& settings, const std::string& key, const std::string& value) {
    const SettingSpec* spec = findSetting(key);
    if (spec == nullptr || key != spec->key) {
        throw InputError("--vary " + key + ": unknown setting (use the names of a scene file's render block)");
    }
    setSetting(settings, *spec, value, "--vary " + key);
}

}  // namespace photon
