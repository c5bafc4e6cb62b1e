#include "core/settings/setting_specs.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <limits>

#include "core/system/error.h"

namespace photon {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

SettingSpec integer(const char* key, const char* flag, const char* help, std::uint32_t RenderSettings::*member,
                    double lo, double hi) {
    SettingSpec s{key, flag, help, SettingKind::Integer, {lo, hi}, {}, {}, {}, {}, {}};
    s.get = [member](const RenderSettings& r) { return double(r.*member); };
    s.set = [member](RenderSettings& r, double v) { r.*member = static_cast<std::uint32_t>(v); };
    return s;
}

SettingSpec number(const char* key, const char* flag, const char* help, float RenderSettings::*member, Range range) {
    SettingSpec s{key, flag, help, SettingKind::Number, range, {}, {}, {}, {}, {}};
    s.get = [member](const RenderSettings& r) { return double(r.*member); };
    s.set = [member](RenderSettings& r, double v) { r.*member = static_cast<float>(v); };
    return s;
}

SettingSpec flag(const char* key, const char* flagName, const char* help, bool RenderSettings::*member) {
    SettingSpec s{key, flagName, help, SettingKind::Flag, {0.0, 1.0}, {}, {}, {}, {}, {}};
    s.get = [member](const RenderSettings& r) { return r.*member ? 1.0 : 0.0; };
    s.set = [member](RenderSettings& r, double v) { r.*member = v != 0.0; };
    return s;
}

template <typename E>
SettingSpec choice(const char* key, const char* flagName, const char* help, E RenderSettings::*member) {
    SettingSpec s{key, flagName, help, SettingKind::Choice, {}, choices(E{}), {}, {}, {}, {}};
    s.getName = [member](const RenderSettings& r) { return std::string(toString(r.*member)); };
    s.setName = [member](RenderSettings& r, const std::string& name) { return parse(name, r.*member); };
    return s;
}

// Query radii: r² must be a normal float and 1/r² finite, far from both ends.
constexpr Range kRadius{1e-15, 1e15};
constexpr Range kWavelength{360.0, 830.0};  // nm: the visible range the observer covers

// Settings whose 0 means "not set": the radii (automatic) and the wavelength (sampled).
bool zeroIsUnset(const SettingSpec& spec) { return spec.range.lo == kRadius.lo || spec.range.lo == kWavelength.lo; }

std::vector<SettingSpec> makeSpecs() {
    using R = RenderSettings;
    return {
        integer("width", "--width", "Image width in pixels", &R::width, 1, 16384),
        integer("height", "--height", "Image height in pixels", &R::height, 1, 16384),
        integer("photons", "--photons", "Photon paths emitted per frame (both passes)", &R::photons, 1, PHOTON_PATHS_MAX),
        integer("frames", "--frames", "Frames averaged into the image", &R::frames, 1, 1000000),
        number("caustic_fraction", "--caustic-fraction", "Share of photons aimed at specular objects",
               &R::causticFraction, {0.0, 0.99}),
        choice("estimator", "--estimator", "Radiance estimate", &R::estimator),
        choice("kernel", "--kernel", "Density kernel", &R::kernel),
        number("radius", "--radius", "Global map query radius (scene units; omit for automatic)", &R::radius, kRadius),
        number("caustic_radius", "--caustic-radius", "Caustic map query radius (omit for automatic)", &R::causticRadius,
               kRadius),
        number("volume_radius", "--volume-radius", "Volume map beam radius in media (omit for automatic)",
               &R::volumeRadius, kRadius),
        integer("k", "--k", "Photons of the k-nearest estimator", &R::k, 1, KNN_MAX),
        number("alpha", "--alpha", "Progressive radius reduction alpha", &R::alpha, {0.01, 0.99}),
        choice("global", "--global", "Indirect light from the global map", &R::globalMode),
        integer("gather_rays", "--gather-rays", "Final-gather rays per pixel", &R::gatherRays, 1, 1024),
        integer("light_samples", "--light-samples", "Shadow rays per light", &R::lightSamples, 1, 1024),
        integer("max_eye_depth", "--max-depth", "Specular bounces of an eye path", &R::maxEyeDepth, 1, 64),
        integer("eye_splits", "--eye-splits",
                "Glass and mirror-coat interfaces where an eye path follows both reflection and refraction "
                "(Fresnel-weighted) instead of one at random",
                &R::eyeSplits, 0, EYE_SPLITS_MAX),
        integer("max_photon_depth", "--max-photon-depth", "Surfaces a photon may hit", &R::maxPhotonDepth, 1, 64),
        choice("grid", "--grid", "Photon map grid", &R::grid),
        integer("grid_resolution", "--grid-resolution", "k of the bounded k^3 grid", &R::gridResolution, 1, 1024),
        number("cell_size", "--cell-size", "Hashed grid cell edge in query radii", &R::cellSize, {1.0, 64.0}),
        integer("gather_budget", "--gather-budget", "Photons a query visits per cell before subsampling it (0: all)",
                &R::gatherBudget, 0, 1u << 30),
        number("photon_capacity", "--photon-capacity", "Stored photons reserved per global path", &R::photonCapacity,
               {1.0, 64.0}),
        integer("seed", "--seed", "Random seed", &R::seed, 0, 4294967295.0),
        flag("pixel_center", "--pixel-center", "One ray through each pixel centre: no jitter, no depth of field",
             &R::pixelCenter),
        flag("deterministic", "--deterministic",
             "GPUs order the photon maps canonically, so the same seed gives the same image bit for bit (on unless "
             "--no-deterministic, which lets the maps come in atomic order: 1-3% faster a frame)",
             &R::deterministic),
        flag("spectral", "--spectral",
             "Paths carry wavelengths, three a frame, and glass disperses (abbe); RGB otherwise", &R::spectral),
        number("wavelength", "--wavelength",
               "Render at this one wavelength [nm] (implies spectral), shown as grey", &R::wavelength, kWavelength),
        choice("view", "--view", "What to show", &R::view),
        number("exposure", "--exposure", "Exposure in stops (PNG and display)", &R::exposure, {-64.0, 64.0}),
        choice("tonemap", "--tonemap", "Tone curve", &R::tonemap),
        choice("denoise", "--denoise",
               "Filter the image, guided by its albedo, normals, depth and variance (.png and .pfm get the "
               "filtered image, .exr both); on unless given",
               &R::denoise),
        flag("aov", "--aov", "Keep the albedo, normal, depth and variance images; .exr files get them as layers",
             &R::aov),
        flag("reproject", "--reproject",
             "When the camera moves, each pixel keeps the history of where its surface was seen (photon-view, "
             "--camera-path); on in photon-view unless given",
             &R::reproject),
    };
}

[[noreturn]] void fail(const std::string& where, const std::string& reason) { throw InputError(where + ": " + reason); }

std::string expectation(const SettingSpec& spec) {
    if (spec.kind == SettingKind::Integer) {
        return "an integer in [" + formatNumber(spec.range.lo) + ", " + formatNumber(spec.range.hi) + "]";
    }
    return spec.range.describe();
}

void markGiven(RenderSettings& settings, const SettingSpec& spec) {
    settings.given |= std::uint64_t(1) << std::size_t(&spec - settingSpecs().data());
}

// Checks a value of an Integer or Number setting and stores it.
void store(RenderSettings& settings, const SettingSpec& spec, double value, const std::string& shown,
           const std::string& where) {
    if (spec.kind == SettingKind::Integer) {
        if (!(value == std::floor(value) && spec.range.contains(value))) {
            fail(where, "must be " + expectation(spec) + " (got " + shown + ")");
        }
    } else {
        // What the renderer sees is the float: check that, against the bounds as floats, so that
        // 1e-50 is not taken for positive and 0.99 is within [0, 0.99].
        auto f = static_cast<float>(value);
        Range bounds{float(spec.range.lo), float(spec.range.hi), spec.range.openLo, spec.range.openHi};
        if (!std::isfinite(value) || !std::isfinite(f) || !bounds.contains(f)) {
            bool radius = spec.range.lo == kRadius.lo;
            fail(where, "must be " + (std::isfinite(value) ? "" : std::string("a finite number ")) +
                            expectation(spec) + " (got " + shown +
                            (radius && value == 0.0 ? "; omit it for the automatic radius)" : ")"));
        }
        value = f;
    }
    spec.set(settings, value);
    markGiven(settings, spec);
}

}  // namespace

std::pair<std::uint32_t, std::uint32_t> parseImageSize(const std::string& text, const std::string& option) {
    // Digits, 'x', digits: no signs, spaces or exponents; a side of 20 digits is still read (as
    // out of range), not wrapped.
    std::size_t cross = text.find_first_of("xX");
    auto digits = [](const std::string& s) {
        return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    if (cross == std::string::npos || !digits(text.substr(0, cross)) || !digits(text.substr(cross + 1))) {
        throw InputError(option + ": " + quote(text) + " is not WIDTHxHEIGHT (like 640x480)");
    }
    double side[2] = {std::strtod(text.substr(0, cross).c_str(), nullptr), std::strtod(text.substr(cross + 1).c_str(), nullptr)};
    const char* keys[2] = {"width", "height"};
    for (int i = 0; i < 2; ++i) {
        const SettingSpec& spec = *findSetting(keys[i]);
        if (!spec.range.contains(side[i])) {
            throw InputError(option + ": " + quote(text) + ": the " + keys[i] + " " + formatNumber(side[i]) + " is not " +
                             spec.range.describe() + " (" + spec.flag + "'s range)");
        }
    }
    return {std::uint32_t(side[0]), std::uint32_t(side[1])};
}

const std::vector<SettingSpec>& settingSpecs() {
    static const std::vector<SettingSpec> specs = makeSpecs();
    static_assert(sizeof(RenderSettings::given) * 8 == 64, "RenderSettings::given holds 64 settings");
    if (specs.size() > 64) {
        throw std::logic_error("more settings than RenderSettings::given has bits");
    }
    return specs;
}

const SettingSpec* findSetting(const std::string& keyOrFlag) {
    for (const SettingSpec& spec : settingSpecs()) {
        if (keyOrFlag == spec.key || keyOrFlag == spec.flag) {
            return &spec;
        }
    }
    return nullptr;
}

void setSetting(RenderSettings& settings, const SettingSpec& spec, const std::string& text, const std::string& where) {
    if (spec.kind == SettingKind::Choice) {
        if (!spec.setName(settings, text)) {
            fail(where, "unknown value " + quote(text) + " (expected " + spec.choices + ")");
        }
        markGiven(settings, spec);
        return;
    }
    if (spec.kind == SettingKind::Flag) {
        if (text == "true" || text == "1" || text == "on") {
            spec.set(settings, 1.0);
        } else if (text == "false" || text == "0" || text == "off") {
            spec.set(settings, 0.0);
        } else {
            fail(where, "must be true or false (got " + quote(text) + ")");
        }
        markGiven(settings, spec);
        return;
    }
    double value = 0.0;
    if (!parseDecimal(text, value)) {
        fail(where, "must be " + expectation(spec) + " (got '" + text + "', not a number)");
    }
    store(settings, spec, value, text, where);
}

void setSettingNumber(RenderSettings& settings, const SettingSpec& spec, double value, const std::string& shown,
                      const std::string& where) {
    if (spec.kind == SettingKind::Choice) {
        fail(where, "expected a string, one of " + spec.choices + " (got " + shown + ")");
    }
    if (spec.kind == SettingKind::Flag) {
        fail(where, "expected true or false (got " + shown + ")");
    }
    store(settings, spec, value, shown, where);
}

void validateSettings(const RenderSettings& settings) {
    for (const SettingSpec& spec : settingSpecs()) {
        if (spec.kind == SettingKind::Choice) {
            try {
                spec.getName(settings);
            } catch (const std::logic_error&) {
                fail(spec.flag, "unknown value (expected " + spec.choices + ")");
            }
        } else if (spec.kind != SettingKind::Flag) {
            double value = spec.get(settings);
            bool automatic = zeroIsUnset(spec) && value == 0.0;
            if (!automatic) {
                RenderSettings copy = settings;
                store(copy, spec, value, formatNumber(value), spec.flag);
            }
        }
    }
    if (settings.estimator == Estimator::Sppm && settings.globalMode == GlobalMode::FinalGather) {
        fail("--global final-gather", "sppm estimates both maps at the visible point: use --global direct with it");
    }
}

bool isGiven(const RenderSettings& settings, const std::string& key) {
    const SettingSpec* spec = findSetting(key);
    if (spec == nullptr) {
        throw std::logic_error("isGiven: no setting " + key);
    }
    return (settings.given >> std::size_t(spec - settingSpecs().data())) & 1u;
}

void chooseDefaults(RenderSettings& settings, bool timed) {
    if (!isGiven(settings, "estimator") && (timed || settings.frames > 1)) {
        settings.estimator = Estimator::Sppm;
    }
    if (!isGiven(settings, "denoise")) {
        settings.denoise = Denoise::On;
    }
}

void chooseInteractive(RenderSettings& settings) {
    if (!isGiven(settings, "reproject")) {
        settings.reproject = true;
    }
}

void choosePhotons(RenderSettings& settings, bool onCpu) {
    if (isGiven(settings, "photons")) {
        return;
    }
    if (!onCpu) {
        settings.photons = kGpuDefaultPhotons;
        return;
    }
    std::uint64_t pixels = std::uint64_t(settings.width) * settings.height;
    std::uint64_t photons = (pixels / kCpuPixelsPerPhoton + 500) / 1000 * 1000;
    settings.photons = std::uint32_t(std::clamp<std::uint64_t>(photons, kCpuPhotonsMin, kGpuDefaultPhotons));
}

}  // namespace photon
