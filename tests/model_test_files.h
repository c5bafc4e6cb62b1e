// What the model loader tests share: companion files held in memory, the loader's error as a
// string, glTF documents built in code, and small comparisons.
#pragma once

#include "core/loaders/model_loader.h"
#include "shared/light_types.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <glm/gtc/matrix_transform.hpp>
#include <meshoptimizer.h>

#include "core/image/image.h"
#include "core/system/error.h"
#include "shared/material.h"
#include "shared/math.h"
#include "test_util.h"

namespace photon {
namespace test_models {


// ---- Fixtures -------------------------------------------------------------------------------------

// Companion files (MTL, images, .bin buffers) held in memory; a missing one fails as on disk.
struct Files {
    std::map<std::string, std::string> files;

    FileReader reader() const {
        return [this](const std::string& path, const char* what) {
            auto it = files.find(path);
            if (it == files.end()) {
                throw InputError(path + ": cannot open the " + std::string(what) + ": No such file or directory");
            }
            return it->second;
        };
    }
};

inline ModelExtras load(Scene& scene, const std::string& path, const std::string& bytes, const Files& files = {},
                 ModelOptions options = {}) {
    return addModel(scene, path, bytes, options, files.reader());
}

inline std::string errorOf(const std::string& path, const std::string& bytes, const Files& files = {}) {
    try {
        Scene scene;
        load(scene, path, bytes, files);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(loaded)";
}

// A PNG of 2×1 texels (sRGB 255,128,0 and 0,0,255) as bytes.
inline std::string twoTexelPng() {
    std::filesystem::path file = std::filesystem::temp_directory_path() / ("photon-texture-" + std::to_string(::getpid()) + ".png");
    const unsigned char rgb[6] = {255, 128, 0, 0, 0, 255};
    writeRgb8Png(file.string(), rgb, 2, 1);
    std::ifstream in(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::filesystem::remove(file);
    return bytes;
}

inline glm::vec3 texel(const Scene& scene, std::uint32_t texture, std::uint32_t x, std::uint32_t y) {
    const Texture& t = scene.textures[texture];
    glm::uvec2 p = scene.texels[t.offset + y * t.width + x];
    return glm::vec3(float(p.x & 0xffffu), float(p.x >> 16u), float(p.y & 0xffffu)) / 65535.0f;
}

inline float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

inline std::string base64(const std::string& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t n = std::uint32_t(std::uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) n |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) n |= std::uint32_t(std::uint8_t(bytes[i + 2]));
        out += digits[(n >> 18) & 63];
        out += digits[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? digits[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? digits[n & 63] : '=';
    }
    return out;
}

template <typename T>
inline void append(std::string& bytes, const std::vector<T>& values) {
    bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// A glTF of one triangle list: positions (accessor 0), 16-bit indices (accessor 1), texture
// coordinates (accessor 2), in one data-URI buffer; `parts` adds or replaces top-level members.
struct Gltf {
    std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::vector<std::uint16_t> indices = {0, 1, 2};
    std::vector<float> texcoords = {0, 0, 1, 0, 0, 1};
    std::map<std::string, std::string> parts = {
        {"scene", "0"},
        {"scenes", R"([{"nodes": [0]}])"},
        {"nodes", R"([{"mesh": 0}])"},
        {"meshes", R"([{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 2}, "indices": 1, "material": 0}]}])"},
        {"materials", R"([{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 0.125, 1], "metallicFactor": 0}}])"},
    };

    // The triangle `count` times, triangle i in mesh i of material i under root node i.
    void trianglePerMaterial(int count) {
        std::string meshes = "[";
        std::string nodes = "[";
        std::string roots = "[";
        for (int i = 0; i < count; ++i) {
            std::string n = std::to_string(i);
            meshes += (i ? "," : "") + std::string(R"({"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": )") + n + "}]}";
            nodes += (i ? "," : "") + std::string(R"({"mesh": )") + n + "}";
            roots += (i ? "," : "") + n;
        }
        parts["meshes"] = meshes + "]";
        parts["nodes"] = nodes + "]";
        parts["scenes"] = R"([{"nodes": )" + roots + "]}]";
    }

    std::string data() const {
        std::string bytes;
        append(bytes, positions);
        append(bytes, indices);
        while (bytes.size() % 4 != 0) bytes += '\0';
        append(bytes, texcoords);
        return bytes;
    }

    std::string text() const {
        std::string data = this->data();
        std::size_t indexOffset = positions.size() * 4;
        std::size_t texOffset = data.size() - texcoords.size() * 4;
        std::size_t vertices = positions.size() / 3;
        std::ostringstream s;
        s << R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": )" << data.size()
          << R"(, "uri": "data:application/octet-stream;base64,)" << base64(data) << R"("}], "bufferViews": [)"
          << R"({"buffer": 0, "byteOffset": 0, "byteLength": )" << indexOffset << "},"
          << R"({"buffer": 0, "byteOffset": )" << indexOffset << R"(, "byteLength": )" << indices.size() * 2 << "},"
          << R"({"buffer": 0, "byteOffset": )" << texOffset << R"(, "byteLength": )" << texcoords.size() * 4 << "}],"
          << R"("accessors": [{"bufferView": 0, "componentType": 5126, "count": )" << vertices << R"(, "type": "VEC3"},)"
          << R"({"bufferView": 1, "componentType": 5123, "count": )" << indices.size() << R"(, "type": "SCALAR"},)"
          << R"({"bufferView": 2, "componentType": 5126, "count": )" << texcoords.size() / 2 << R"(, "type": "VEC2"}])";
        for (const auto& [key, value] : parts) {
            s << ", \"" << key << "\": " << value;
        }
        s << "}";
        return s.str();
    }
};

inline void expectNear(glm::vec3 a, glm::vec3 b, float tolerance = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

inline const char* const kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

}  // namespace test_models
}  // namespace photon
