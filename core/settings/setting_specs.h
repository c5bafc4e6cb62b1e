// Every render setting once: its name in scene files (and photon-bench's --vary), its command-line
// flag, what it accepts. The scene loader, photon-render, photon-bench and photon-view all parse
// and check settings through this table, so that a value is accepted or refused alike everywhere,
// with one message: "<where>: must be in [lo, hi] (got x)". Only finite values are accepted.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/settings/settings.h"
#include "core/system/numbers.h"

namespace photon {

enum class SettingKind { Integer, Number, Choice, Flag };

struct SettingSpec {
    const char* key;   // in scene files' "render" block and --vary: "cell_size"
    const char* flag;  // on the command line: "--cell-size"
    const char* help;
    SettingKind kind;
    Range range;       // Integer and Number
    std::string choices;  // Choice: "a|b|c"
    // Reads and writes the setting: numbers and integers as double, choices as names, flags as 0/1.
    std::function<double(const RenderSettings&)> get;
    std::function<void(RenderSettings&, double)> set;
    std::function<std::string(const RenderSettings&)> getName;
    std::function<bool(RenderSettings&, const std::string&)> setName;  // false: not a choice
};

const std::vector<SettingSpec>& settingSpecs();

// The setting of a scene-file key or a flag; nullptr if there is none.
const SettingSpec* findSetting(const std::string& keyOrFlag);

// Sets a setting from command-line text ("0.04", "knn", "true"); throws InputError
// "<where>: <reason>" for anything it does not accept.
void setSetting(RenderSettings& settings, const SettingSpec& spec, const std::string& text, const std::string& where);

// The same from a JSON number (Integer, Number) or boolean (Flag); `shown` is the value as written.
void setSettingNumber(RenderSettings& settings, const SettingSpec& spec, double value, const std::string& shown,
                      const std::string& where);

// Every setting in its range (values set directly, as the viewer's HUD does, are checked here);
// throws InputError naming the first bad one by its flag.
void validateSettings(const RenderSettings& settings);

// Whether a file or the command line set the setting of this key (or flag).
bool isGiven(const RenderSettings& settings, const std::string& key);

// What is left to choose once a render's length is known: sppm for a render of more than one frame
// (or of a time), unless an estimator was given.
void chooseDefaults(RenderSettings& settings, bool timed);
// What a program whose camera moves gets unless told: the history follows the camera (reproject).
void chooseInteractive(RenderSettings& settings);

// Photon paths a frame when neither the file nor the command line gives them, for the backend that
// renders: on a GPU kGpuDefaultPhotons; on the host's cores, where a frame's eye pass and gather
// cost as much as tracing a third as many photons as there are pixels, one photon per
// kCpuPixelsPerPhoton pixels, so that a time-limited render gets its frames (the 2-core machine's
// 2-second Cornell box at 640x480: 0.13 relative RMSE at 100k photons a frame, 0.17-0.18 at 500k;
// docs/performance.md, issue 20).
inline constexpr std::uint32_t kGpuDefaultPhotons = 500000;
inline constexpr std::uint32_t kCpuPixelsPerPhoton = 3;
inline constexpr std::uint32_t kCpuPhotonsMin = 20000;
void choosePhotons(RenderSettings& settings, bool onCpu);

// "WIDTHxHEIGHT" (or "WxH" with a capital X) as an option gives an image size: each side in
// --width's and --height's range, or InputError naming `option` and which side is out of range.
std::pair<std::uint32_t, std::uint32_t> parseImageSize(const std::string& text, const std::string& option);

// The default length of photon-render's render without --frames, --time or frames in the scene.
inline constexpr double kDefaultRenderSeconds = 2.0;

}  // namespace photon
