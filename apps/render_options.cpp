#include "render_options.h"

#include <sstream>

#include "core/settings/setting_specs.h"
#include "core/system/error.h"

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

void addRenderOptions(CLI::App& app, RenderOptions& o) {
    for (const SettingSpec& spec : settingSpecs()) {
        std::string help = spec.help;
        if (spec.kind == SettingKind::Flag) {
            app.add_flag(spec.flag, o.flags[spec.flag], help);
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
    app.add_flag("--allow-outside-paths", o.paths.allowOutside,
                 "Let model files read buffers, images, MTL files and textures outside their own folder");
}

void applyRenderOptions(const CLI::App& app, const RenderOptions& o, RenderSettings& settings) {
    for (const SettingSpec& spec : settingSpecs()) {
        if (app.count(spec.flag) == 0) {
            continue;
        }
        if (spec.kind == SettingKind::Flag) {
            setSetting(settings, spec, "true", spec.flag);
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
