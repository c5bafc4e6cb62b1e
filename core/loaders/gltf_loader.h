// The glTF loader's state and its parts, one file each: gltf_loader.cpp (the buffers, their
// views and accessors, the node walk with its cameras and lights, and the entry, addGltfModel),
// gltf_materials.cpp (materials and textures) and gltf_geometry.cpp (the primitives' attributes,
// indices and triangles). Every member checks what it reads and fails with the file, the JSON
// path and the reason.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
// Images are decoded by texture_loader.cpp (keepImage in gltf_loader.cpp), never by tinygltf's stb copy: the
// same macros as loader_packages.cpp, so that the fuzz build's single tinygltf agrees.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>

#include "core/loaders/gltf_compression.h"
#include "core/loaders/gltf_document.h"
#include "core/loaders/model_loader.h"
#include "core/loaders/texture_loader.h"
#include "core/system/error.h"
#include "shared/math.h"

namespace photon::gltf {

// One file being loaded into a scene: what it holds (tinygltf's model) and what of it the scene
// has taken so far.
struct Loader {
    Scene& scene;
    const std::string& path;
    const ModelOptions& options;
    const FileReader& read;
    tinygltf::Model model;
    std::vector<std::uint32_t> materials;  // scene material of each glTF material, NONE until used
    std::vector<std::array<std::uint32_t, 2>> textures;  // scene texture of each glTF texture (sRGB,
                                                         // linear), NONE until used
    std::uint32_t defaultMaterial = NONE;
    ModelExtras extras;
    std::set<int> fallbackBuffers;                             // EXT_meshopt_compression's, without data
    std::map<std::size_t, std::vector<unsigned char>> decoded;  // decompressed buffer views by index
    std::size_t decodedBytes = 0;
    // What the node walk met, to say why a file gave no triangles.
    struct {
        std::size_t nodes = 0, meshes = 0, primitives = 0, surfaces = 0, triangles = 0;
    } census;

    [[noreturn]] void fail(const std::string& where, const std::string& reason) const {
        throw InputError(path + ": " + where + ": " + reason);
    }

    static std::string at(const char* array, std::size_t index) { return std::string("/") + array + "/" + std::to_string(index); }

    // ---- Buffer views ----------------------------------------------------------------------------

    struct Bytes {
        const unsigned char* data = nullptr;
        std::size_t size = 0;
    };

    // `length` bytes at `offset` of a buffer, checked to lie within it.
    Bytes slice(int buffer, std::size_t offset, std::size_t length, const std::string& where) const;

    // The bytes of a buffer view: a slice of its buffer, or, for an EXT_meshopt_compression view,
    // the data decoded (once) from the compressed slice its extension names.
    Bytes bufferView(int index, const std::string& where);

    // A non-negative integral number of an extension object (tinygltf keeps large ones as reals).
    static bool integer(const tinygltf::Value& object, const char* key, std::size_t& out) {
        if (!object.Has(key) || !object.Get(key).IsNumber()) {
            return false;
        }
        double x = object.Get(key).GetNumberAsDouble();
        if (!(x >= 0.0 && x <= 9007199254740992.0 && x == std::floor(x))) {
            return false;
        }
        out = std::size_t(x);
        return true;
    }

    static std::string name(const tinygltf::Value& object, const char* key, const char* fallback) {
        return object.Has(key) && object.Get(key).IsString() ? object.Get(key).Get<std::string>() : fallback;
    }

    // The value that an extension's string `key` names in `table`; any other string fails, with
    // the names the table knows.
    template <typename E, std::size_t N>
    E named(const tinygltf::Value& object, const char* key, const char* fallback,
            const std::pair<const char*, E> (&table)[N], const std::string& here) const {
        std::string given = name(object, key, fallback);
        std::string expected;
        for (const auto& [text, value] : table) {
            if (given == text) {
                return value;
            }
            expected += (expected.empty() ? "" : "|") + std::string(text);
        }
        fail(here + "/" + key, "unknown " + std::string(key) + " " + quote(given) + " (expected " + expected + ")");
    }

    Bytes decompressed(std::size_t index, const tinygltf::Value& ext, const std::string& here);

    // ---- Accessors -------------------------------------------------------------------------------

    // The elements of an accessor over some bytes, after checking that all `count` elements lie
    // within them.
    struct View {
        const unsigned char* data = nullptr;
        std::size_t stride = 0;
        std::size_t count = 0;
        int componentType = 0;
        int components = 0;
        bool normalized = false;
    };

    const tinygltf::Accessor& accessor(int index, const std::string& where) const;

    // Accessor `index` over `bytes` (its buffer view's, or a decoder's), from `offset` with
    // `byteStride` (0: tightly packed).
    View layout(int index, Bytes bytes, std::size_t offset, std::size_t byteStride, const std::string& viewWhere) const;

    View view(int index, const std::string& where);

    // One component as a number, by the glTF rules: normalized integers map to [0, 1] (unsigned)
    // or [-1, 1] (signed; the most negative value is clamped to -1, so that 0 stays exact), other
    // integers are taken as they are (KHR_mesh_quantization's positions and texture coordinates).
    static float component(const unsigned char* e, int type, bool normalized);

    // The component types an attribute may have: floats, and KHR_mesh_quantization's bytes and
    // shorts (normals and tangents only signed and normalized, being unit vectors).
    static bool allowedType(const std::string& attribute, int type, bool normalized);

    // Vectors of N components of attribute `name` (accessor `index`), every value finite.
    template <int N>
    std::vector<glm::vec<N, float>> attribute(const View& v, int index, const std::string& name) const;

    std::vector<std::uint32_t> indices(int index, std::size_t vertices, const std::string& where);

    // ---- Materials -------------------------------------------------------------------------------

    // KHR_materials_volume_scatter (proposed, glTF PR #2453): the volume scatters as well as
    // absorbs. Its attenuation (KHR_materials_volume) is then the extinction σt, multiscatterColor
    // the albedo seen after many bounces, made the single-scattering albedo by Kulla and Conty's fit
    // (2017), and scatterAnisotropy Henyey–Greenstein's g. A thin-walled or clear volume has none.
    void volumeScatter(const tinygltf::Value& scatter, Material& m);

    static double number(const tinygltf::Value& object, const char* key, double fallback) {
        if (object.IsObject() && object.Has(key) && object.Get(key).IsNumber()) {
            return object.Get(key).GetNumberAsDouble();
        }
        return fallback;
    }

    // KHR_materials_dispersion's 20 / V_d, which applies to volumes only (thin walls: none).
    float dispersion(const tinygltf::Value& extension, const std::string& here, std::uint32_t flags) const;

    static double clamp01(double x) { return std::isfinite(x) ? std::clamp(x, 0.0, 1.0) : 0.0; }

    // The scene texture of glTF texture `index` in an encoding, decoded once for each.
    std::uint32_t texture(int index, const std::string& where, TextureEncoding encoding);

    // A material's use of a texture: the texture seen through the textureInfo's
    // KHR_texture_transform (offset, rotation, scale), if it has one. Texture coordinate sets
    // other than TEXCOORD_0 are not read: the texture is left out, as docs/scenes.md says.
    std::uint32_t textureInfo(int index, int texCoord, const tinygltf::ExtensionMap& extensions, const std::string& where,
                              TextureEncoding encoding);

    // glTF's metallic-roughness material with its extensions as Photon's MATERIAL_PBR
    // (shared/pbr.h; the table of docs/scenes.md).
    std::uint32_t material(int index, const std::string& where);

    // ---- Geometry ---------------------------------------------------------------------------------

    // POSITION, NORMAL, TANGENT and TEXCOORD_0 into the mesh, each from the View that `viewOf`
    // gives for (name, accessor): the accessor's buffer view, or a decoded Draco attribute.
    template <typename ViewOf>
    void readAttributes(const tinygltf::Primitive& p, Mesh& mesh, const std::string& here, ViewOf viewOf);

    // The vertex order of a plain primitive: its indices, or 0, 1, 2, ...
    std::vector<std::uint32_t> vertexOrder(const tinygltf::Primitive& p, std::size_t vertices, const std::string& here);

    // A KHR_draco_mesh_compression primitive: its faces and the attributes the extension names come
    // from the Draco mesh (as the accessors' component types); others from their accessors.
    std::vector<std::uint32_t> dracoGeometry(const tinygltf::Primitive& p, const tinygltf::Value& ext, Mesh& mesh,
                                             const std::string& here);

    // Triangles from a vertex order by the primitive's mode: lists, strips (every other one turned
    // back to keep the winding) and fans.
    static std::vector<glm::uvec3> assemble(int mode, const std::vector<std::uint32_t>& order);

    void primitive(const tinygltf::Primitive& p, const glm::mat4& transform, const std::string& here);

    // Why a file that parsed gave no triangles, for its message.
    std::string noTriangles() const;

    static glm::mat4 localTransform(const tinygltf::Node& n);

    void camera(int index, const glm::mat4& world, const std::string& here);

    void light(const tinygltf::Node& node, const glm::mat4& world, const std::string& here);

    void nodes();
};

}  // namespace photon::gltf
