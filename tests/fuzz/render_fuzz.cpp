// libFuzzer target for everything between a scene file and an image: a scene (JSON) and settings
// chosen from the input (finite or not: NaN, ±inf, denormals, huge and zero values too), rendered
// at a tiny size through the CPU backend, under AddressSanitizer and UBSan. Every input must either
// be refused with InputError or give an image whose every value is finite. Anything else (another
// exception, a crash, a sanitizer report, a NaN, a hang) is a bug.
//
// Input: scene JSON, a NUL byte, then the bytes that choose the settings. An input that starts
// with a NUL builds its scene from those bytes instead: random objects, materials and lights, their
// numbers mostly ordinary and sometimes extreme, written as a scene file for the loader to check.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "core/image.h"
#include "core/scene_loader.h"
#include "core/setting_specs.h"
#include "cpu/cpu_backend.h"

namespace {

// Values that break renderers, and ordinary ones.
const char* const kValues[] = {"nan", "inf", "-inf", "1e-45", "1e-38", "-1e-45", "0", "-0", "1", "-1", "0.5", "2",
                               "16", "64", "1e9", "1e15", "1e38", "1e39", "3.4e38", "4294967295", "4294967296",
                               "-4294967296", "1e-15", "0.99", "1e300", "true", "false", "cell", "radius", "knn",
                               "progressive", "bounded", "hashed", "final-gather", "grid", "caustic"};

std::string valueFrom(FuzzedDataProvider& data) {
    switch (data.ConsumeIntegralInRange(0, 2)) {
        case 0: return kValues[data.ConsumeIntegralInRange<std::size_t>(0, sizeof(kValues) / sizeof(kValues[0]) - 1)];
        case 1: {  // any sign and magnitude between 2^-60 and 2^60
            double fraction = data.ConsumeFloatingPointInRange(-1.0, 1.0);
            return photon::formatNumber(std::ldexp(fraction, data.ConsumeIntegralInRange(-60, 60)));
        }
        default: return std::to_string(data.ConsumeIntegralInRange<std::int64_t>(-100000, 100000));
    }
}

// A number for the generated scenes: mostly of a scene's scale, sometimes extreme.
std::string numberFrom(FuzzedDataProvider& data) {
    if (data.ConsumeIntegralInRange(0, 9) == 0) {
        const char* extremes[] = {"0", "-0", "1e-45", "1e-38", "1e-20", "1e20", "1e38", "3.4e38", "-1e38", "1e-7"};
        return extremes[data.ConsumeIntegralInRange(0, 9)];
    }
    return photon::formatNumber(data.ConsumeFloatingPointInRange(-4.0, 4.0));
}

std::string vec3From(FuzzedDataProvider& data) {
    std::string x = numberFrom(data);
    std::string y = numberFrom(data);
    std::string z = numberFrom(data);
    return "[" + x + ", " + y + ", " + z + "]";
}

std::string colourFrom(FuzzedDataProvider& data) {
    std::string c[3];
    for (std::string& v : c) {
        v = photon::formatNumber(data.ConsumeIntegralInRange(0, 10) / 10.0);
    }
    return "[" + c[0] + ", " + c[1] + ", " + c[2] + "]";
}

std::string generatedScene(FuzzedDataProvider& data) {
    std::string text = "{\"camera\": {\"position\": " + vec3From(data) + ", \"look_at\": " + vec3From(data) +
                       ", \"fov\": " + photon::formatNumber(data.ConsumeFloatingPointInRange(1.0, 170.0)) + "},";
    const char* materials[] = {R"("m0": {"type": "diffuse", "albedo": ALBEDO})", R"("m1": {"type": "mirror"})",
                               R"("m2": {"type": "glass", "ior": IOR})",
                               R"("m3": {"type": "glossy", "albedo": [0.3, 0.3, 0.3], "specular": [0.5, 0.5, 0.5], "roughness": 0.2})",
                               R"("m4": {"type": "reflective", "albedo": [0.4, 0.2, 0.1], "reflectance": [0.5, 0.5, 0.5]})"};
    text += "\"materials\": {";
    for (int m = 0; m < 5; ++m) {
        std::string entry = materials[m];
        auto put = [&](const std::string& key, const std::string& value) {
            std::size_t at = entry.find(key);
            if (at != std::string::npos) {
                entry.replace(at, key.size(), value);
            }
        };
        put("ALBEDO", colourFrom(data));
        put("IOR", photon::formatNumber(data.ConsumeFloatingPointInRange(0.5, 3.0)));
        text += (m ? ", " : "") + entry;
    }
    text += "}, \"objects\": [";
    int objects = data.ConsumeIntegralInRange(0, 6);
    for (int i = 0; i < objects; ++i) {
        std::string material = "\"material\": \"m" + std::to_string(data.ConsumeIntegralInRange(0, 4)) + "\"";
        switch (data.ConsumeIntegralInRange(0, 4)) {
            case 0: text += "{\"type\": \"sphere\", \"center\": " + vec3From(data) + ", \"radius\": " + numberFrom(data); break;
            case 1: text += "{\"type\": \"plane\", \"point\": " + vec3From(data) + ", \"normal\": " + vec3From(data); break;
            case 2:
                text += "{\"type\": \"quad\", \"corner\": " + vec3From(data) + ", \"edge_u\": " + vec3From(data) +
                        ", \"edge_v\": " + vec3From(data);
                break;
            case 3: {
                std::string a = vec3From(data);
                std::string b = vec3From(data);
                text += "{\"type\": \"triangle\", \"vertices\": [" + a + ", " + b + ", " + vec3From(data) + "]";
                break;
            }
            default: text += "{\"type\": \"box\", \"min\": [-1, -1, -1], \"max\": " + vec3From(data); break;
        }
        text += ", " + material + "}" + (i + 1 < objects ? ", " : "");
    }
    text += "], \"lights\": [";
    int lights = data.ConsumeIntegralInRange(1, 3);
    for (int i = 0; i < lights; ++i) {
        switch (data.ConsumeIntegralInRange(0, 3)) {
            case 0: text += "{\"type\": \"point\", \"position\": " + vec3From(data); break;
            case 1:
                text += "{\"type\": \"spot\", \"position\": " + vec3From(data) + ", \"direction\": " + vec3From(data) +
                        ", \"angle\": " + photon::formatNumber(data.ConsumeFloatingPointInRange(0.001, 90.0));
                break;
            case 2: text += "{\"type\": \"sphere\", \"center\": " + vec3From(data) + ", \"radius\": " + numberFrom(data); break;
            default:
                text += "{\"type\": \"quad\", \"corner\": " + vec3From(data) + ", \"edge_u\": " + vec3From(data) +
                        ", \"edge_v\": " + vec3From(data);
                break;
        }
        text += ", \"power\": " + numberFrom(data) + "}" + (i + 1 < lights ? ", " : "");
    }
    return text + "]}";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
    std::string input(reinterpret_cast<const char*>(bytes), size);
    std::size_t nul = input.find('\0');
    std::string sceneText = input.substr(0, nul);
    FuzzedDataProvider data(bytes + std::min(size, nul == std::string::npos ? size : nul + 1),
                            nul == std::string::npos ? 0 : size - nul - 1);
    try {
        photon::Scene scene = photon::loadSceneJson(nul == 0 ? generatedScene(data) : sceneText, "fuzz.json");
        photon::RenderSettings settings = scene.render;
        int changes = data.ConsumeIntegralInRange(0, 6);
        const auto& specs = photon::settingSpecs();
        for (int i = 0; i < changes; ++i) {
            const photon::SettingSpec& spec = specs[data.ConsumeIntegralInRange<std::size_t>(0, specs.size() - 1)];
            photon::setSetting(settings, spec, valueFrom(data), spec.flag);
        }
        // Tiny, so that each input renders in milliseconds (what is refused at these sizes is
        // refused at any size).
        settings.width = std::min(settings.width, 12u);
        settings.height = std::min(settings.height, 10u);
        settings.photons = std::min(settings.photons, 1500u);
        settings.frames = std::min(settings.frames, 2u);
        settings.gatherRays = std::min(settings.gatherRays, 4u);
        settings.lightSamples = std::min(settings.lightSamples, 2u);
        settings.gridResolution = std::min(settings.gridResolution, 64u);
        auto backend = photon::createCpuBackend();
        backend->setScene(scene);
        backend->setSettings(settings);
        for (std::uint32_t f = 0; f < settings.frames; ++f) {
            backend->renderFrame();
        }
        if (!photon::allFinite(backend->image())) {
            std::fprintf(stderr, "render_fuzz: a non-finite pixel\n");
            std::abort();
        }
        if (std::getenv("PHOTON_FUZZ_TRACE")) {
            std::fprintf(stderr, "rendered %ux%u, %u photons\n", settings.width, settings.height, settings.photons);
        }
    } catch (const photon::InputError& e) {
        // Refused: the expected outcome for many inputs.
        if (std::getenv("PHOTON_FUZZ_TRACE")) {
            std::fprintf(stderr, "refused: %s\n", e.what());
        }
    }
    return 0;
}
