// libFuzzer target for everything between a scene file and an image: a scene (JSON) and settings
// chosen from the input (finite or not: NaN, ±inf, denormals, huge and zero values too), rendered
// at a tiny size through the CPU backend, under AddressSanitizer and UBSan. Every input must either
// be refused with InputError or give an image whose every value is finite. Anything else (another
// exception, a crash, a sanitizer report, a NaN, a hang) is a bug.
//
// Input: scene JSON (optionally followed by the files its mesh objects read, after a line
// "#--- name" each: companions.h), a NUL byte, then the bytes that choose the settings. An input that starts
// with a NUL builds its scene from those bytes instead: random objects, materials and lights, their
// numbers mostly ordinary and sometimes extreme, written as a scene file for the loader to check,
// and mesh objects of generated OBJ files (held in memory) with texture coordinates, normals and
// MTL materials with a base-colour texture, so that what the model loaders produce is shaded too.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <string>

#include "companions.h"
#include "core/loaders/model_loader.h"
#include "core/loaders/scene_loader.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "render_check.h"

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

// Files the scene's meshes read (OBJ, MTL, image), by name.
using Files = photon::fuzz::Companions;

// Texture coordinates: mostly within a few repeats, sometimes extreme (a texture lookup must hold
// any finite value).
std::string texcoordFrom(FuzzedDataProvider& data) {
    if (data.ConsumeIntegralInRange(0, 7) == 0) {
        const char* extremes[] = {"0", "1", "-1e-45", "1e30", "-1e30", "3.4e38", "0.9999999", "-0.5"};
        return extremes[data.ConsumeIntegralInRange(0, 7)];
    }
    return photon::formatNumber(data.ConsumeFloatingPointInRange(-2.0, 3.0));
}

// An OBJ of a few faces with texture coordinates (and sometimes normals) and its MTL, whose
// material may have a base-colour texture: a binary PPM of up to 4×4 texels (or bytes that are
// not one). Returns the OBJ's name.
std::string generatedObj(FuzzedDataProvider& data, Files& files, int index) {
    std::string name = "m" + std::to_string(index) + ".obj";
    std::string obj;
    bool material = data.ConsumeBool();
    if (material) {
        std::string mtl = "newmtl t\nKd";
        for (int c = 0; c < 3; ++c) {
            mtl += " " + photon::formatNumber(data.ConsumeIntegralInRange(0, 10) / 10.0);
        }
        mtl += "\n";
        switch (data.ConsumeIntegralInRange(0, 3)) {
            case 0: mtl += "Ks 0.5 0.5 0.5\nNs " + photon::formatNumber(data.ConsumeFloatingPointInRange(0.0, 1000.0)) + "\n"; break;
            case 1: mtl += "d 0.2\nNi " + photon::formatNumber(data.ConsumeFloatingPointInRange(0.5, 3.0)) + "\n"; break;
            case 2: mtl += "Ke 1 1 1\n"; break;
            default: break;
        }
        if (data.ConsumeIntegralInRange(0, 3) != 0) {
            std::string image = "t" + std::to_string(index) + ".ppm";
            mtl += "map_Kd " + image + "\n";
            int w = data.ConsumeIntegralInRange(1, 4);
            int h = data.ConsumeIntegralInRange(1, 4);
            std::string ppm = "P6\n" + std::to_string(w) + " " + std::to_string(h) + "\n255\n";
            for (int i = 0; i < 3 * w * h; ++i) {
                ppm += char(data.ConsumeIntegral<std::uint8_t>());
            }
            if (data.ConsumeIntegralInRange(0, 9) == 0) {
                ppm.resize(ppm.size() / 2);  // truncated
            }
            files[image] = ppm;
        }
        std::string mtlName = "m" + std::to_string(index) + ".mtl";
        files[mtlName] = mtl;
        obj += "mtllib " + mtlName + "\nusemtl t\n";
    }
    // Vertices about a circle and texture coordinates about the unit square, moved by a byte each,
    // so that short inputs still make faces with area; some are anything at all.
    int vertices = data.ConsumeIntegralInRange(3, 8);
    for (int i = 0; i < vertices; ++i) {
        double angle = 6.283185307179586 * i / vertices;
        auto near = [&](double base) { return photon::formatNumber(base + data.ConsumeIntegral<std::int8_t>() / 64.0); };
        if (data.ConsumeIntegralInRange(0, 7) == 0) {
            std::string x = numberFrom(data);
            std::string y = numberFrom(data);
            obj += "v " + x + " " + y + " " + numberFrom(data) + "\n";
        } else {
            std::string x = near(std::cos(angle));
            std::string y = near(std::sin(angle));
            obj += "v " + x + " " + y + " " + near(0.0) + "\n";
        }
        if (data.ConsumeIntegralInRange(0, 7) == 0) {
            std::string u = texcoordFrom(data);
            obj += "vt " + u + " " + texcoordFrom(data) + "\n";
        } else {
            std::string u = near(0.5 + 0.5 * std::cos(angle));
            obj += "vt " + u + " " + near(0.5 + 0.5 * std::sin(angle)) + "\n";
        }
    }
    bool normals = data.ConsumeBool();
    if (normals) {
        for (int i = 0; i < vertices; ++i) {
            std::string x = numberFrom(data);
            std::string y = numberFrom(data);
            obj += "vn " + x + " " + y + " " + numberFrom(data) + "\n";
        }
    }
    int faces = data.ConsumeIntegralInRange(1, 6);
    for (int f = 0; f < faces; ++f) {
        obj += "f";
        int corners = data.ConsumeIntegralInRange(3, 4);
        // Mostly distinct corners (random ones are often degenerate, and the mesh then refused).
        bool distinct = data.ConsumeIntegralInRange(0, 3) != 0;
        int first = data.ConsumeIntegralInRange(0, vertices - 1);
        for (int c = 0; c < corners; ++c) {
            std::string v = std::to_string(distinct ? (first + c) % vertices + 1 : data.ConsumeIntegralInRange(1, vertices));
            obj += " " + v + "/" + std::to_string(data.ConsumeIntegralInRange(1, vertices)) +
                   (normals ? "/" + std::to_string(data.ConsumeIntegralInRange(1, vertices)) : std::string());
        }
        obj += "\n";
    }
    files[name] = obj;
    return name;
}

std::string generatedScene(FuzzedDataProvider& data, Files& files) {
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
        switch (data.ConsumeIntegralInRange(0, 5)) {
            case 5: {
                // A mesh: its file's materials (textured) or a scene material, under a transform.
                text += "{\"type\": \"mesh\", \"file\": \"" + generatedObj(data, files, i) + "\"";
                if (data.ConsumeBool()) {
                    text += ", \"transform\": {\"scale\": " + photon::formatNumber(data.ConsumeFloatingPointInRange(0.1, 4.0)) +
                            ", \"translate\": " + vec3From(data) + "}";
                }
                if (data.ConsumeBool()) {
                    text += "}" + std::string(i + 1 < objects ? ", " : "");
                    continue;
                }
                break;
            }
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
    // A scene file may carry the files of its mesh objects (companions.h).
    Files files;
    std::string sceneText = photon::fuzz::splitCompanions(input.substr(0, nul), files);
    FuzzedDataProvider data(bytes + std::min(size, nul == std::string::npos ? size : nul + 1),
                            nul == std::string::npos ? 0 : size - nul - 1);
    try {
        std::string text = nul == 0 ? generatedScene(data, files) : sceneText;
        photon::FileReader read = photon::fuzz::companionReader(files);
        photon::Scene scene = photon::loadSceneJson(text, "fuzz.json", "", read);
        photon::RenderSettings settings = scene.render;
        int changes = data.ConsumeIntegralInRange(0, 6);
        const auto& specs = photon::settingSpecs();
        for (int i = 0; i < changes; ++i) {
            const photon::SettingSpec& spec = specs[data.ConsumeIntegralInRange<std::size_t>(0, specs.size() - 1)];
            photon::setSetting(settings, spec, valueFrom(data), spec.flag);
        }
        // Tiny, so that each input renders in milliseconds (what is refused at these sizes is
        // refused at any size).
        photon::fuzz::renderTiny(scene, settings, 12, 10, 1500);
    } catch (const photon::InputError& e) {
        // Refused: the expected outcome for many inputs.
        if (std::getenv("PHOTON_FUZZ_TRACE")) {
            std::fprintf(stderr, "refused: %s\n", e.what());
        }
    }
    return 0;
}
