// glTF 2.0, .gltf (external or data-URI buffers) and .glb (tinygltf): the default scene's node
// hierarchy with its transforms, indexed triangles (lists, strips, fans), normals, texture
// coordinates, the metallic-roughness material with its textures and extensions, cameras and
// KHR_lights_punctual. tinygltf parses the JSON and
// gathers the buffers and images; every accessor, index and node is checked here.
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
// Images are decoded by texture_loader.cpp (keepImage below), never by tinygltf's stb copy: the
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

namespace photon {
namespace {

constexpr std::size_t kTinygltfMessageMax = 300;  // bytes of tinygltf's message that an error quotes
constexpr double kWattsPerLumen = 1.0 / 683.0;  // glTF's photometric units taken at 555 nm

// The extensions a file may require: every other one in extensionsRequired is refused by name.
const char* const kSupportedRequired[] = {
    "KHR_lights_punctual",          "KHR_materials_transmission", "KHR_materials_ior",
    "KHR_materials_emissive_strength", "KHR_materials_volume",    "KHR_texture_transform",
    "KHR_mesh_quantization",        "EXT_meshopt_compression",    "KHR_draco_mesh_compression",
    "KHR_materials_dispersion",     "KHR_materials_volume_scatter",
};

// EXT_meshopt_compression's modes and filters by their names in the file.
const std::pair<const char*, MeshoptMode> kMeshoptModes[] = {
    {"ATTRIBUTES", MeshoptMode::Attributes}, {"TRIANGLES", MeshoptMode::Triangles}, {"INDICES", MeshoptMode::Indices}};
const std::pair<const char*, MeshoptFilter> kMeshoptFilters[] = {{"NONE", MeshoptFilter::None},
                                                                 {"OCTAHEDRAL", MeshoptFilter::Octahedral},
                                                                 {"QUATERNION", MeshoptFilter::Quaternion},
                                                                 {"EXPONENTIAL", MeshoptFilter::Exponential}};

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
    Bytes slice(int buffer, std::size_t offset, std::size_t length, const std::string& where) const {
        if (buffer < 0 || std::size_t(buffer) >= model.buffers.size()) {
            fail(where, "buffer " + std::to_string(buffer) + " does not exist");
        }
        if (fallbackBuffers.count(buffer) != 0) {
            fail(where, "buffer " + std::to_string(buffer) + " is an EXT_meshopt_compression fallback, which has no data");
        }
        const std::vector<unsigned char>& data = model.buffers[std::size_t(buffer)].data;
        if (offset > data.size() || length > data.size() - offset) {
            fail(where, "extends beyond its buffer of " + std::to_string(data.size()) + " bytes");
        }
        return {data.data() + offset, length};
    }

    // The bytes of a buffer view: a slice of its buffer, or, for an EXT_meshopt_compression view,
    // the data decoded (once) from the compressed slice its extension names.
    Bytes bufferView(int index, const std::string& where) {
        if (index < 0 || std::size_t(index) >= model.bufferViews.size()) {
            fail(where, "buffer view " + std::to_string(index) + " does not exist");
        }
        const tinygltf::BufferView& bv = model.bufferViews[std::size_t(index)];
        std::string here = at("bufferViews", std::size_t(index));
        auto meshopt = bv.extensions.find("EXT_meshopt_compression");
        if (meshopt != bv.extensions.end()) {
            return decompressed(std::size_t(index), meshopt->second, here + "/extensions/EXT_meshopt_compression");
        }
        return slice(bv.buffer, bv.byteOffset, bv.byteLength, here);
    }

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

    Bytes decompressed(std::size_t index, const tinygltf::Value& ext, const std::string& here) {
        auto done = decoded.find(index);
        if (done != decoded.end()) {
            return {done->second.data(), done->second.size()};
        }
        MeshoptView v;
        std::size_t buffer = 0;
        std::size_t offset = 0;
        std::size_t length = 0;
        if (!ext.IsObject() || !integer(ext, "buffer", buffer) || !integer(ext, "byteLength", length) ||
            !integer(ext, "byteStride", v.stride) || !integer(ext, "count", v.count) ||
            (ext.Has("byteOffset") && !integer(ext, "byteOffset", offset)) || buffer > std::size_t(INT32_MAX)) {
            fail(here, "buffer, byteLength, byteStride and count must be integers of at least 0 (and byteOffset, if given)");
        }
        v.mode = named(ext, "mode", "", kMeshoptModes, here);
        v.filter = named(ext, "filter", "NONE", kMeshoptFilters, here);
        // What the view says it holds is what it must decode to: its accessors are checked against it.
        const tinygltf::BufferView& bv = model.bufferViews[index];
        if (v.stride == 0 || bv.byteLength % v.stride != 0 || bv.byteLength / v.stride != v.count) {
            fail(here, std::to_string(v.count) + " elements of " + std::to_string(v.stride) +
                           " bytes are not the buffer view's byteLength of " + std::to_string(bv.byteLength));
        }
        if (bv.byteLength > kModelFileLimit - decodedBytes) {
            fail(here, "more than 1 GiB of decompressed data in the file");
        }
        Bytes source = slice(int(buffer), offset, length, here);
        try {
            std::vector<unsigned char> bytes = decodeMeshopt(v, source.data, source.size);
            decodedBytes += bytes.size();
            auto& kept = decoded[index] = std::move(bytes);
            return {kept.data(), kept.size()};
        } catch (const DecodeError& e) {
            fail(here, e.what());
        }
    }

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

    const tinygltf::Accessor& accessor(int index, const std::string& where) const {
        if (index < 0 || std::size_t(index) >= model.accessors.size()) {
            fail(where, "accessor " + std::to_string(index) + " does not exist");
        }
        const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
        if (a.sparse.isSparse) {
            fail(at("accessors", std::size_t(index)), "sparse accessors are not supported");
        }
        return a;
    }

    // Accessor `index` over `bytes` (its buffer view's, or a decoder's), from `offset` with
    // `byteStride` (0: tightly packed).
    View layout(int index, Bytes bytes, std::size_t offset, std::size_t byteStride, const std::string& viewWhere) const {
        const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
        std::string here = at("accessors", std::size_t(index));
        int componentSize = tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType));
        int components = tinygltf::GetNumComponentsInType(std::uint32_t(a.type));
        if (componentSize <= 0 || components <= 0) {
            fail(here, "unknown component type or type");
        }
        std::size_t element = std::size_t(componentSize) * std::size_t(components);
        std::size_t stride = byteStride > 0 ? byteStride : element;
        if (stride < element) {
            fail(viewWhere, "byteStride " + std::to_string(stride) + " is less than an element");
        }
        if (a.count > 0 && (offset > bytes.size || (a.count - 1) > (bytes.size - offset) / stride ||
                            offset + (a.count - 1) * stride + element > bytes.size)) {
            fail(here, std::to_string(a.count) + " elements extend beyond buffer view " + std::to_string(a.bufferView));
        }
        View v;
        v.data = bytes.data + offset;
        v.stride = stride;
        v.count = a.count;
        v.componentType = a.componentType;
        v.components = components;
        v.normalized = a.normalized;
        return v;
    }

    View view(int index, const std::string& where) {
        const tinygltf::Accessor& a = accessor(index, where);
        if (a.bufferView < 0 || std::size_t(a.bufferView) >= model.bufferViews.size()) {
            fail(at("accessors", std::size_t(index)), "no buffer view (bufferView " + std::to_string(a.bufferView) + ")");
        }
        Bytes bytes = bufferView(a.bufferView, at("accessors", std::size_t(index)));
        return layout(index, bytes, a.byteOffset, model.bufferViews[std::size_t(a.bufferView)].byteStride,
                      at("bufferViews", std::size_t(a.bufferView)));
    }

    // One component as a number, by the glTF rules: normalized integers map to [0, 1] (unsigned)
    // or [-1, 1] (signed; the most negative value is clamped to -1, so that 0 stays exact), other
    // integers are taken as they are (KHR_mesh_quantization's positions and texture coordinates).
    static float component(const unsigned char* e, int type, bool normalized) {
        switch (type) {
            case TINYGLTF_COMPONENT_TYPE_BYTE: {
                auto x = std::int8_t(e[0]);
                return normalized ? std::max(float(x) / 127.0f, -1.0f) : float(x);
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                return normalized ? float(e[0]) / 255.0f : float(e[0]);
            case TINYGLTF_COMPONENT_TYPE_SHORT: {
                std::int16_t x;
                std::memcpy(&x, e, 2);
                return normalized ? std::max(float(x) / 32767.0f, -1.0f) : float(x);
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                std::uint16_t x;
                std::memcpy(&x, e, 2);
                return normalized ? float(x) / 65535.0f : float(x);
            }
            default: {
                float x;
                std::memcpy(&x, e, 4);
                return x;
            }
        }
    }

    // The component types an attribute may have: floats, and KHR_mesh_quantization's bytes and
    // shorts (normals and tangents only signed and normalized, being unit vectors).
    static bool allowedType(const std::string& attribute, int type, bool normalized) {
        if (type == TINYGLTF_COMPONENT_TYPE_FLOAT) {
            return true;
        }
        if (attribute == "NORMAL" || attribute == "TANGENT") {
            return normalized && (type == TINYGLTF_COMPONENT_TYPE_BYTE || type == TINYGLTF_COMPONENT_TYPE_SHORT);
        }
        return type == TINYGLTF_COMPONENT_TYPE_BYTE || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
               type == TINYGLTF_COMPONENT_TYPE_SHORT || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    }

    // Vectors of N components of attribute `name` (accessor `index`), every value finite.
    template <int N>
    std::vector<glm::vec<N, float>> attribute(const View& v, int index, const std::string& name) const {
        std::string here = at("accessors", std::size_t(index));
        if (v.components != N) {
            fail(here, "expected " + std::to_string(N) + " components, got " + std::to_string(v.components));
        }
        if (!allowedType(name, v.componentType, v.normalized)) {
            fail(here, name + (name == "NORMAL" || name == "TANGENT"
                                   ? " must be floats, or normalized signed bytes or shorts"
                                   : " must be floats, bytes or shorts"));
        }
        int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(v.componentType));
        std::vector<glm::vec<N, float>> out(v.count);
        for (std::size_t i = 0; i < v.count; ++i) {
            const unsigned char* e = v.data + i * v.stride;
            for (int c = 0; c < N; ++c) {
                float x = component(e + c * size, v.componentType, v.normalized);
                if (!std::isfinite(x)) {
                    fail(here, "element " + std::to_string(i) + " is not finite");
                }
                out[i][c] = x;
            }
        }
        return out;
    }

    std::vector<std::uint32_t> indices(int index, std::size_t vertices, const std::string& where) {
        View v = view(index, where);
        std::string here = at("accessors", std::size_t(index));
        if (v.components != 1) {
            fail(here, "indices must be scalars");
        }
        std::vector<std::uint32_t> out(v.count);
        for (std::size_t i = 0; i < v.count; ++i) {
            const unsigned char* e = v.data + i * v.stride;
            std::uint32_t x = 0;
            if (v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
                x = e[0];
            } else if (v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
                std::uint16_t u;
                std::memcpy(&u, e, 2);
                x = u;
            } else if (v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
                std::memcpy(&x, e, 4);
            } else {
                fail(here, "indices must be unsigned bytes, shorts or ints");
            }
            if (x >= vertices) {
                fail(here, "index " + std::to_string(x) + " at element " + std::to_string(i) + " out of range (" +
                               std::to_string(vertices) + " vertices)");
            }
            out[i] = x;
        }
        return out;
    }

    // ---- Materials -------------------------------------------------------------------------------

    // KHR_materials_volume_scatter (proposed, glTF PR #2453): the volume scatters as well as
    // absorbs. Its attenuation (KHR_materials_volume) is then the extinction σt, multiscatterColor
    // the albedo seen after many bounces, made the single-scattering albedo by Kulla and Conty's fit
    // (2017), and scatterAnisotropy Henyey–Greenstein's g. A thin-walled or clear volume has none.
    void volumeScatter(const tinygltf::Value& scatter, Material& m) {
        if (!scatter.IsObject() || (m.flags & MATERIAL_FLAG_THIN_WALLED) != 0u || m.attenuation == glm::vec3(0.0f)) {
            return;
        }
        Medium md = homogeneousMedium();
        for (int c = 0; c < 3; ++c) {
            double a = 0.0;
            if (scatter.Has("multiscatterColor") && scatter.Get("multiscatterColor").IsArray() &&
                scatter.Get("multiscatterColor").ArrayLen() == 3 && scatter.Get("multiscatterColor").Get(c).IsNumber()) {
                a = clamp01(scatter.Get("multiscatterColor").Get(c).GetNumberAsDouble());
            }
            double root = 4.09712 + 4.20863 * a - std::sqrt(9.59217 + 41.6808 * a + 17.7126 * a * a);
            double albedo = std::clamp(1.0 - root * root, 0.0, 1.0);
            md.scattering[c] = float(albedo * m.attenuation[c]);
            md.absorption[c] = float((1.0 - albedo) * m.attenuation[c]);
        }
        md.g = float(std::clamp(number(scatter, "scatterAnisotropy", 0.0), -0.99, 0.99));
        m.medium = scene.addMedium(md);
        m.attenuation = glm::vec3(0.0f);
    }

    static double number(const tinygltf::Value& object, const char* key, double fallback) {
        if (object.IsObject() && object.Has(key) && object.Get(key).IsNumber()) {
            return object.Get(key).GetNumberAsDouble();
        }
        return fallback;
    }

    // KHR_materials_dispersion's 20 / V_d, which applies to volumes only (thin walls: none).
    float dispersion(const tinygltf::Value& extension, const std::string& here, std::uint32_t flags) const {
        if (!extension.IsObject() || !extension.Has("dispersion")) {
            return 0.0f;
        }
        const tinygltf::Value& v = extension.Get("dispersion");
        double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
        if (!(d >= 0.0 && d <= 20.0)) {  // an Abbe number of at least 1, as the scene files' abbe
            fail(here + "/extensions/KHR_materials_dispersion/dispersion", "must be a number from 0 to 20 (20 / Abbe number)");
        }
        return (flags & MATERIAL_FLAG_THIN_WALLED) != 0u ? 0.0f : float(d);
    }

    static double clamp01(double x) { return std::isfinite(x) ? std::clamp(x, 0.0, 1.0) : 0.0; }

    // The scene texture of glTF texture `index` in an encoding, decoded once for each.
    std::uint32_t texture(int index, const std::string& where, TextureEncoding encoding) {
        if (index < 0 || std::size_t(index) >= model.textures.size()) {
            fail(where, "texture " + std::to_string(index) + " does not exist");
        }
        std::uint32_t& cached = textures[std::size_t(index)][encoding == TextureEncoding::Srgb ? 0 : 1];
        if (cached != NONE) {
            return cached;
        }
        const tinygltf::Texture& t = model.textures[std::size_t(index)];
        std::string here = at("textures", std::size_t(index));
        if (t.source < 0 || std::size_t(t.source) >= model.images.size()) {
            fail(here, "image " + std::to_string(t.source) + " does not exist");
        }
        auto wrap = [](int mode) {
            return mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? WRAP_CLAMP
                   : mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? WRAP_MIRRORED_REPEAT
                                                                   : WRAP_REPEAT;
        };
        std::uint32_t wrapS = WRAP_REPEAT;
        std::uint32_t wrapT = WRAP_REPEAT;
        if (t.sampler >= 0) {
            if (std::size_t(t.sampler) >= model.samplers.size()) {
                fail(here, "sampler " + std::to_string(t.sampler) + " does not exist");
            }
            wrapS = wrap(model.samplers[std::size_t(t.sampler)].wrapS);
            wrapT = wrap(model.samplers[std::size_t(t.sampler)].wrapT);
        }
        const tinygltf::Image& image = model.images[std::size_t(t.source)];
        std::string bytes(image.image.begin(), image.image.end());
        if (bytes.empty() && !image.uri.empty() && image.uri.rfind("data:", 0) != 0) {
            // tinygltf keeps going past an external image it could not read: read it again for the reason.
            std::string file = namedFile(folderOf(path), image.uri);
            checkNamedFile(path, file, "image", options.paths);
            bytes = read(file, "image");
        }
        cached = addImageTexture(scene, bytes, wrapS, wrapT, path + ": " + at("images", std::size_t(t.source)), encoding);
        return cached;
    }

    // A material's use of a texture: the texture seen through the textureInfo's
    // KHR_texture_transform (offset, rotation, scale), if it has one. Texture coordinate sets
    // other than TEXCOORD_0 are not read: the texture is left out, as docs/scenes.md says.
    std::uint32_t textureInfo(int index, int texCoord, const tinygltf::ExtensionMap& extensions, const std::string& where,
                              TextureEncoding encoding) {
        auto it = extensions.find("KHR_texture_transform");
        if (it != extensions.end() && it->second.IsObject() && it->second.Has("texCoord") &&
            it->second.Get("texCoord").IsInt()) {
            texCoord = it->second.Get("texCoord").Get<int>();
        }
        if (index < 0 || texCoord != 0) {
            return NONE;
        }
        std::uint32_t t = texture(index, where, encoding);
        if (it == extensions.end()) {
            return t;
        }
        const tinygltf::Value& x = it->second;
        auto pair = [&](const char* key, double fallback, int c) {
            if (x.IsObject() && x.Has(key) && x.Get(key).IsArray() && x.Get(key).ArrayLen() == 2 &&
                x.Get(key).Get(c).IsNumber()) {
                return x.Get(key).Get(c).GetNumberAsDouble();
            }
            return fallback;
        };
        double rotation = number(x, "rotation", 0.0);
        double ox = pair("offset", 0.0, 0);
        double oy = pair("offset", 0.0, 1);
        double sx = pair("scale", 1.0, 0);
        double sy = pair("scale", 1.0, 1);
        for (double v : {rotation, ox, oy, sx, sy}) {
            if (!std::isfinite(v) || std::abs(v) > 1e6) {
                fail(where + "/extensions/KHR_texture_transform", "offset, rotation and scale must be finite");
            }
        }
        // (s', t') = T · R · S · (s, t) with R = [cos r, sin r; −sin r, cos r] (the extension's).
        double c = std::cos(rotation);
        double sn = std::sin(rotation);
        glm::vec3 rowS(float(c * sx), float(sn * sy), float(ox));
        glm::vec3 rowT(float(-sn * sx), float(c * sy), float(oy));
        return scene.addTextureView(t, rowS, rowT);
    }

    // glTF's metallic-roughness material with its extensions as Photon's MATERIAL_PBR
    // (shared/pbr.h; the table of docs/scenes.md).
    std::uint32_t material(int index, const std::string& where) {
        if (options.material != NONE) {
            return options.material;
        }
        if (index < 0) {
            if (defaultMaterial == NONE) {
                // The glTF default: white, fully metallic and rough (the specification's values).
                defaultMaterial = scene.addMaterial(path + "#default", makePbr(glm::vec3(1.0f), 1.0f, 1.0f));
            }
            return defaultMaterial;
        }
        if (std::size_t(index) >= model.materials.size()) {
            fail(where, "material " + std::to_string(index) + " does not exist");
        }
        if (materials[std::size_t(index)] != NONE) {
            return materials[std::size_t(index)];
        }
        const tinygltf::Material& g = model.materials[std::size_t(index)];
        std::string here = at("materials", std::size_t(index));
        const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
        glm::vec4 base(1.0f);
        for (int c = 0; c < 4 && std::size_t(c) < pbr.baseColorFactor.size(); ++c) {
            base[c] = float(clamp01(pbr.baseColorFactor[std::size_t(c)]));
        }
        Material m = makePbr(glm::vec3(base), float(clamp01(pbr.metallicFactor)), float(clamp01(pbr.roughnessFactor)));
        m.alpha = base.w;
        auto extension = [&](const char* name) {
            auto it = g.extensions.find(name);
            return it == g.extensions.end() ? tinygltf::Value() : it->second;
        };
        m.transmission = float(clamp01(number(extension("KHR_materials_transmission"), "transmissionFactor", 0.0)));
        double ior = number(extension("KHR_materials_ior"), "ior", 1.5);
        if (ior == 0.0) {
            // The ratified schema allows exactly 0 besides ≥ 1: a reflectance of 1 (f0 from ior),
            // which no refracting material has.
            fail(here + "/extensions/KHR_materials_ior/ior", "0 (a reflectance of 1) is not supported: use 1 to 10");
        }
        if (!(ior >= 1.0 && ior <= 10.0)) {
            fail(here + "/extensions/KHR_materials_ior/ior", "must be from 1 to 10");
        }
        m.ior = float(ior);
        // KHR_materials_volume: a body of glass (refracting, absorbing) rather than a thin sheet.
        tinygltf::Value volume = extension("KHR_materials_volume");
        if (!(number(volume, "thicknessFactor", 0.0) > 0.0)) {
            m.flags |= MATERIAL_FLAG_THIN_WALLED;
        }
        double distance = number(volume, "attenuationDistance", HUGE_VAL);
        if (!(distance > 0.0)) {
            fail(here + "/extensions/KHR_materials_volume/attenuationDistance", "must be positive");
        }
        if (std::isfinite(distance) && volume.IsObject() && volume.Has("attenuationColor") &&
            volume.Get("attenuationColor").IsArray() && volume.Get("attenuationColor").ArrayLen() == 3) {
            for (int c = 0; c < 3; ++c) {
                const tinygltf::Value& v = volume.Get("attenuationColor").Get(c);
                double colour = v.IsNumber() ? std::clamp(v.GetNumberAsDouble(), 1e-6, 1.0) : 1.0;
                m.attenuation[c] = float(-std::log(colour) / distance);  // Beer–Lambert: σ = −ln(c)/d
            }
        }
        volumeScatter(extension("KHR_materials_volume_scatter"), m);
        m.dispersion = dispersion(extension("KHR_materials_dispersion"), here, m.flags);
        if (!g.doubleSided) {
            m.flags |= MATERIAL_FLAG_SINGLE_SIDED;
        }
        if (g.alphaMode == "MASK") {
            m.flags |= MATERIAL_FLAG_ALPHA_MASK;
            m.alphaCutoff = float(std::isfinite(g.alphaCutoff) ? std::max(g.alphaCutoff, 0.0) : 0.5);
        } else if (g.alphaMode == "BLEND") {
            m.flags |= MATERIAL_FLAG_ALPHA_BLEND;
        } else if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty()) {
            fail(here + "/alphaMode", "unknown alphaMode '" + g.alphaMode.substr(0, 40) + "'");
        }
        m.albedoTexture = textureInfo(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                      pbr.baseColorTexture.extensions, here + "/pbrMetallicRoughness/baseColorTexture",
                                      TextureEncoding::Srgb);
        m.metallicRoughnessTexture =
            textureInfo(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                        pbr.metallicRoughnessTexture.extensions, here + "/pbrMetallicRoughness/metallicRoughnessTexture",
                        TextureEncoding::Linear);
        m.normalTexture = textureInfo(g.normalTexture.index, g.normalTexture.texCoord, g.normalTexture.extensions,
                                      here + "/normalTexture", TextureEncoding::Linear);
        m.normalScale = std::isfinite(g.normalTexture.scale) ? float(std::clamp(g.normalTexture.scale, -100.0, 100.0)) : 1.0f;
        glm::vec3 emission(0.0f);
        for (int c = 0; c < 3 && std::size_t(c) < g.emissiveFactor.size(); ++c) {
            emission[c] = float(clamp01(g.emissiveFactor[std::size_t(c)]));
        }
        double strength = number(extension("KHR_materials_emissive_strength"), "emissiveStrength", 1.0);
        if (!(strength >= 0.0 && strength < 1e6)) {
            fail(here + "/extensions/KHR_materials_emissive_strength/emissiveStrength", "must be from 0 to 1e6");
        }
        m.emission = emission * float(strength);
        if (!isBlack(m.emission)) {
            m.emissionTexture = textureInfo(g.emissiveTexture.index, g.emissiveTexture.texCoord, g.emissiveTexture.extensions,
                                            here + "/emissiveTexture", TextureEncoding::Srgb);
        }
        std::string name = g.name.empty() ? std::to_string(index) : g.name;
        materials[std::size_t(index)] = scene.addMaterial(path + "#" + name, m);
        return materials[std::size_t(index)];
    }

    // ---- Geometry ---------------------------------------------------------------------------------

    // POSITION, NORMAL, TANGENT and TEXCOORD_0 into the mesh, each from the View that `viewOf`
    // gives for (name, accessor): the accessor's buffer view, or a decoded Draco attribute.
    template <typename ViewOf>
    void readAttributes(const tinygltf::Primitive& p, Mesh& mesh, const std::string& here, ViewOf viewOf) {
        auto accessorOf = [&](const char* name) {
            auto it = p.attributes.find(name);
            return it == p.attributes.end() ? -1 : it->second;
        };
        int position = accessorOf("POSITION");
        if (position < 0) {
            fail(here, "a primitive without POSITION");
        }
        mesh.positions = attribute<3>(viewOf("POSITION", position), position, "POSITION");
        if (int normal = accessorOf("NORMAL"); normal >= 0) {
            mesh.normals = attribute<3>(viewOf("NORMAL", normal), normal, "NORMAL");
        }
        if (int tangent = accessorOf("TANGENT"); tangent >= 0) {
            mesh.tangents = attribute<4>(viewOf("TANGENT", tangent), tangent, "TANGENT");
        }
        if (int texcoord = accessorOf("TEXCOORD_0"); texcoord >= 0) {
            mesh.texcoords = attribute<2>(viewOf("TEXCOORD_0", texcoord), texcoord, "TEXCOORD_0");
        }
        std::size_t n = mesh.positions.size();
        if ((!mesh.normals.empty() && mesh.normals.size() != n) || (!mesh.tangents.empty() && mesh.tangents.size() != n) ||
            (!mesh.texcoords.empty() && mesh.texcoords.size() != n)) {
            fail(here, "NORMAL, TANGENT or TEXCOORD_0 has another count than POSITION");
        }
    }

    // The vertex order of a plain primitive: its indices, or 0, 1, 2, ...
    std::vector<std::uint32_t> vertexOrder(const tinygltf::Primitive& p, std::size_t vertices, const std::string& here) {
        if (p.indices >= 0) {
            return indices(p.indices, vertices, here);
        }
        std::vector<std::uint32_t> order(vertices);
        for (std::uint32_t i = 0; i < order.size(); ++i) {
            order[i] = i;
        }
        return order;
    }

    // A KHR_draco_mesh_compression primitive: its faces and the attributes the extension names come
    // from the Draco mesh (as the accessors' component types); others from their accessors.
    std::vector<std::uint32_t> dracoGeometry(const tinygltf::Primitive& p, const tinygltf::Value& ext, Mesh& mesh,
                                             const std::string& here) {
        if (!ext.IsObject() || !ext.Get("bufferView").IsInt() || !ext.Get("attributes").IsObject()) {
            fail(here, "needs a bufferView and attributes");
        }
        Bytes bytes = bufferView(ext.Get("bufferView").Get<int>(), here + "/bufferView");
        std::unique_ptr<DracoMesh> draco;
        try {
            draco = std::make_unique<DracoMesh>(bytes.data, bytes.size);
        } catch (const DecodeError& e) {
            fail(here, e.what());
        }
        const tinygltf::Value& ids = ext.Get("attributes");
        std::vector<unsigned char> values;
        readAttributes(p, mesh, here, [&](const char* name, int index) {
            if (!ids.Has(name)) {
                return view(index, here);
            }
            std::string where = here + "/attributes/" + name;
            const tinygltf::Value& id = ids.Get(name);
            if (!id.IsInt() || id.Get<int>() < 0) {
                fail(where, "not a Draco attribute id");
            }
            const tinygltf::Accessor& a = accessor(index, here);
            if (a.count != draco->points()) {
                fail(at("accessors", std::size_t(index)), "count " + std::to_string(a.count) + ", but the Draco mesh has " +
                                                              std::to_string(draco->points()) + " points");
            }
            try {
                values = draco->attribute(std::uint32_t(id.Get<int>()), a.componentType,
                                          tinygltf::GetNumComponentsInType(std::uint32_t(a.type)));
            } catch (const DecodeError& e) {
                fail(where, e.what());
            }
            return layout(index, {values.data(), values.size()}, 0, 0, where);
        });
        std::vector<std::uint32_t> order;
        try {
            for (glm::uvec3 t : draco->triangles()) {
                order.insert(order.end(), {t.x, t.y, t.z});
            }
        } catch (const DecodeError& e) {
            fail(here, e.what());
        }
        return order;
    }

    // Triangles from a vertex order by the primitive's mode: lists, strips (every other one turned
    // back to keep the winding) and fans.
    static std::vector<glm::uvec3> assemble(int mode, const std::vector<std::uint32_t>& order) {
        std::vector<glm::uvec3> triangles;
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            for (std::size_t i = 0; i + 2 < order.size(); i += 3) {
                triangles.emplace_back(order[i], order[i + 1], order[i + 2]);
            }
        } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            for (std::size_t i = 0; i + 2 < order.size(); ++i) {
                triangles.push_back(i % 2 == 0 ? glm::uvec3(order[i], order[i + 1], order[i + 2])
                                                : glm::uvec3(order[i + 1], order[i], order[i + 2]));
            }
        } else {
            for (std::size_t i = 1; i + 1 < order.size(); ++i) {
                triangles.emplace_back(order[0], order[i], order[i + 1]);
            }
        }
        return triangles;
    }

    void primitive(const tinygltf::Primitive& p, const glm::mat4& transform, const std::string& here) {
        census.primitives += 1;
        if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP && p.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            return;  // points and lines have no surface
        }
        census.surfaces += 1;
        Mesh mesh;
        auto draco = p.extensions.find("KHR_draco_mesh_compression");
        if (draco != p.extensions.end()) {
            // Draco decodes faces: a triangle list whatever the mode says.
            mesh.triangles = assemble(TINYGLTF_MODE_TRIANGLES,
                                      dracoGeometry(p, draco->second, mesh, here + "/extensions/KHR_draco_mesh_compression"));
        } else {
            readAttributes(p, mesh, here, [&](const char*, int index) { return view(index, here); });
            mesh.triangles = assemble(p.mode, vertexOrder(p, mesh.positions.size(), here));
        }
        if (mesh.triangles.empty()) {
            return;
        }
        census.triangles += mesh.triangles.size();
        mesh.materials.assign(mesh.triangles.size(), material(p.material, here + "/material"));
        scene.addMesh(mesh, transform);
    }

    // Why a file that parsed gave no triangles, for its message.
    std::string noTriangles() const {
        if (census.nodes == 0) {
            return model.scenes.empty() ? "the file has no nodes" : "its scene has no nodes";
        }
        if (census.meshes == 0) {
            return "none of its nodes has a mesh";
        }
        if (census.primitives == 0) {
            return "its meshes have no primitives";
        }
        if (census.surfaces == 0) {
            return "its primitives are points or lines only";
        }
        return "its triangle primitives have fewer than 3 vertices";
    }

    static glm::mat4 localTransform(const tinygltf::Node& n) {
        if (n.matrix.size() == 16) {
            glm::mat4 m;
            for (int i = 0; i < 16; ++i) {
                m[i / 4][i % 4] = float(n.matrix[std::size_t(i)]);  // column-major
            }
            return m;
        }
        glm::mat4 m(1.0f);
        if (n.translation.size() == 3) {
            m = glm::translate(m, glm::vec3(float(n.translation[0]), float(n.translation[1]), float(n.translation[2])));
        }
        if (n.rotation.size() == 4) {
            glm::quat q(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2]));
            m = m * glm::mat4_cast(glm::normalize(q));
        }
        if (n.scale.size() == 3) {
            m = glm::scale(m, glm::vec3(float(n.scale[0]), float(n.scale[1]), float(n.scale[2])));
        }
        return m;
    }

    void camera(int index, const glm::mat4& world, const std::string& here) {
        if (extras.hasCamera || index < 0) {
            return;
        }
        if (std::size_t(index) >= model.cameras.size()) {
            fail(here + "/camera", "camera " + std::to_string(index) + " does not exist");
        }
        const tinygltf::Camera& c = model.cameras[std::size_t(index)];
        if (c.type != "perspective") {
            return;  // orthographic: a framing camera instead
        }
        double fov = c.perspective.yfov * 180.0 / 3.14159265358979323846;
        CameraDesc d;
        d.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
        glm::vec3 forward = glm::vec3(world * glm::vec4(0, 0, -1, 0));
        glm::vec3 up = glm::vec3(world * glm::vec4(0, 1, 0, 0));
        if (!(fov > 0.1 && fov < 179.0) || !(glm::length(forward) > 0.0f) || !(glm::length(up) > 0.0f) ||
            !std::isfinite(d.position.x + d.position.y + d.position.z)) {
            fail(at("cameras", std::size_t(index)), "not a usable perspective camera");
        }
        d.lookAt = d.position + glm::normalize(forward);
        d.up = glm::normalize(up);
        d.fovY = float(fov);
        extras.camera = d;
        extras.hasCamera = true;
    }

    void light(const tinygltf::Node& node, const glm::mat4& world, const std::string& here) {
        auto it = node.extensions.find("KHR_lights_punctual");
        if (it == node.extensions.end() || !it->second.IsObject() || !it->second.Has("light")) {
            return;
        }
        const tinygltf::Value& index = it->second.Get("light");
        if (!index.IsInt() || index.Get<int>() < 0 || std::size_t(index.Get<int>()) >= model.lights.size()) {
            fail(here + "/extensions/KHR_lights_punctual/light", "no such light");
        }
        std::size_t i = std::size_t(index.Get<int>());
        const tinygltf::Light& l = model.lights[i];
        std::string where = "/extensions/KHR_lights_punctual/lights/" + std::to_string(i);
        glm::vec3 colour(1.0f);
        for (int c = 0; c < 3 && std::size_t(c) < l.color.size(); ++c) {
            colour[c] = float(clamp01(l.color[std::size_t(c)]));
        }
        if (!(std::isfinite(l.intensity) && l.intensity > 0.0 && l.intensity < 1e12)) {
            fail(where, "intensity must be positive and finite");
        }
        if (scene.lights.size() >= LIGHTS_MAX) {
            fail(where, "more than " + std::to_string(LIGHTS_MAX) + " lights");
        }
        glm::vec3 position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
        glm::vec3 direction = glm::vec3(world * glm::vec4(0, 0, -1, 0));
        if (!(glm::length(direction) > 0.0f) || !std::isfinite(position.x + position.y + position.z)) {
            fail(here, "the light's node transform is degenerate");
        }
        direction = glm::normalize(direction);
        float intensity = float(l.intensity * kWattsPerLumen);  // W/sr, or W/m² for directional
        if (l.type == "directional") {
            scene.addDirectionalLight(direction, colour * intensity);
        } else if (l.type == "point") {
            scene.addPointLight(position, colour * (intensity * 4.0f * PI));
        } else if (l.type == "spot") {
            double outer = std::clamp(l.spot.outerConeAngle * 180.0 / 3.14159265358979323846, 0.01, 90.0);
            double inner = std::clamp(l.spot.innerConeAngle * 180.0 / 3.14159265358979323846, 0.0, outer);
            scene.addSpotLight(position, direction, glm::vec3(1.0f), float(outer), float(inner));
            // Photon's spot is given by its flux: the peak intensity I takes I·2π(1 - cos outer)·mean falloff.
            Light& spot = scene.lights.back();
            spot.power = colour * (intensity * 2.0f * PI * spot.spotOuter * spot.falloffMean);
        } else {
            fail(where + "/type", "unknown light type " + quote(l.type));
        }
        extras.lights += 1;
    }

    void nodes() {
        std::vector<int> roots;
        if (!model.scenes.empty()) {
            std::size_t s = model.defaultScene >= 0 ? std::size_t(model.defaultScene) : 0;
            if (s >= model.scenes.size()) {
                fail("/scene", "scene " + std::to_string(s) + " does not exist");
            }
            roots = model.scenes[s].nodes;
        } else {
            std::vector<bool> child(model.nodes.size(), false);
            for (const tinygltf::Node& n : model.nodes) {
                for (int c : n.children) {
                    if (c >= 0 && std::size_t(c) < child.size()) {
                        child[std::size_t(c)] = true;
                    }
                }
            }
            for (std::size_t i = 0; i < model.nodes.size(); ++i) {
                if (!child[i]) {
                    roots.push_back(int(i));
                }
            }
        }
        // Depth first without recursion; a node met again on its own path is a cycle.
        struct Visit {
            int node;
            glm::mat4 parent;
            std::size_t depth;
        };
        std::vector<Visit> stack;
        for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
            stack.push_back({*it, options.transform, 0});
        }
        std::vector<int> pathNodes;
        std::size_t visits = 0;
        while (!stack.empty()) {
            Visit v = stack.back();
            stack.pop_back();
            pathNodes.resize(v.depth);
            if (v.node < 0 || std::size_t(v.node) >= model.nodes.size()) {
                fail(pathNodes.empty() ? "/scenes" : at("nodes", std::size_t(pathNodes.back())) + "/children",
                     "node " + std::to_string(v.node) + " does not exist");
            }
            std::string here = at("nodes", std::size_t(v.node));
            if (std::find(pathNodes.begin(), pathNodes.end(), v.node) != pathNodes.end()) {
                fail(here, "a cycle in the node hierarchy");
            }
            if (++visits > 1000000) {
                fail(here, "more than a million node instances");
            }
            const tinygltf::Node& n = model.nodes[std::size_t(v.node)];
            glm::mat4 world = v.parent * localTransform(n);
            census.nodes += 1;
            if (n.mesh >= 0) {
                census.meshes += 1;
                if (std::size_t(n.mesh) >= model.meshes.size()) {
                    fail(here + "/mesh", "mesh " + std::to_string(n.mesh) + " does not exist");
                }
                const tinygltf::Mesh& mesh = model.meshes[std::size_t(n.mesh)];
                for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
                    primitive(mesh.primitives[p], world, at("meshes", std::size_t(n.mesh)) + "/primitives/" + std::to_string(p));
                }
            }
            if (options.cameraAndLights) {
                camera(n.camera, world, here);
                light(n, world, here);
            }
            pathNodes.push_back(v.node);
            for (auto it = n.children.rbegin(); it != n.children.rend(); ++it) {
                stack.push_back({*it, world, v.depth + 1});
            }
        }
    }
};

// tinygltf reads external buffers and images through the loader's file reader, each checked to lie
// in the model's folder tree first. The first refusal or read error is kept whole for the message
// (tinygltf would wrap it in its own words).
struct FileSystem {
    const FileReader& read;
    const std::string& model;
    const PathPolicy& paths;
    std::string error;
};

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto* fs = static_cast<FileSystem*>(user);
    try {
        std::string file = namedFile("", path);
        checkNamedFile(fs->model, file, "file", fs->paths);
        std::string bytes = fs->read(file, "buffer or image");
        out->assign(bytes.begin(), bytes.end());
        return true;
    } catch (const InputError& e) {
        if (fs->error.empty()) {
            fs->error = e.what();
        }
        *err += std::string(e.what()) + "\n";
        return false;
    }
}

bool fileExists(const std::string&, void*) { return true; }  // reading says why a file is missing
std::string expandPath(const std::string& path, void*) { return path; }
bool writeWholeFile(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

// Images stay encoded here; the material that uses one decodes it (texture_loader.cpp).
// tinygltf hands over an image in a buffer view as a pointer and the view's byteLength, unchecked
// against the buffer (which it has read already, into the model it is filling: `user`).
bool keepImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
               const unsigned char* bytes, int size, void* user) {
    if (image->bufferView >= 0) {
        const auto* model = static_cast<const tinygltf::Model*>(user);
        const tinygltf::BufferView& bv = model->bufferViews[std::size_t(image->bufferView)];  // checked by tinygltf
        const std::vector<unsigned char>& data = model->buffers[std::size_t(bv.buffer)].data;
        if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset) {
            *err += "/images/" + std::to_string(index) + ": buffer view " + std::to_string(image->bufferView) +
                    " extends beyond its buffer of " + std::to_string(data.size()) + " bytes\n";
            return false;
        }
    }
    image->image.assign(bytes, bytes + std::max(size, 0));
    image->as_is = true;
    return true;
}

}  // namespace

ModelExtras addGltfModel(Scene& scene, const std::string& path, const std::string& bytes, const ModelOptions& options,
                         const FileReader& read) {
    Loader loader{scene, path, options, read, {}, {}, {}, NONE, {}, {}, {}, 0, {}};
    if (bytes.size() > 0xffffffffu) {
        throw InputError(path + ": larger than 4 GiB");
    }
    GltfDocument doc = prepareGltf(path, bytes);
    loader.fallbackBuffers = doc.fallbackBuffers;
    tinygltf::TinyGLTF gltf;
    FileSystem fs{read, path, options.paths, {}};
    gltf.SetFsCallbacks({fileExists, expandPath, readWholeFile, writeWholeFile, &fs});
    gltf.SetImageLoader(keepImage, &loader.model);
    std::string err;
    std::string warn;
    std::string folder = folderOf(path);
    std::string base = folder.empty() ? "." : folder;
    const std::string& data = doc.bytes;
    bool ok = doc.binary ? gltf.LoadBinaryFromMemory(&loader.model, &err, &warn,
                                                     reinterpret_cast<const unsigned char*>(data.data()),
                                                     unsigned(data.size()), base)
                         : gltf.LoadASCIIFromString(&loader.model, &err, &warn, data.data(), unsigned(data.size()), base);
    if (!ok && !fs.error.empty()) {
        throw InputError(fs.error);
    }
    if (!ok) {
        // tinygltf's first line, cut: some of its messages quote a value of the file whole.
        std::string first = printable(err.substr(0, std::min(err.find('\n'), kTinygltfMessageMax)));
        if (err.find('\n') > kTinygltfMessageMax && err.size() > kTinygltfMessageMax) {
            first += "...";
        }
        throw InputError(path + ": " + (first.empty() ? std::string("not a glTF file") : first));
    }
    for (std::size_t i = 0; i < loader.model.extensionsRequired.size(); ++i) {
        const std::string& e = loader.model.extensionsRequired[i];
        if (std::none_of(std::begin(kSupportedRequired), std::end(kSupportedRequired), [&](const char* s) { return e == s; })) {
            loader.fail("/extensionsRequired/" + std::to_string(i), "the required extension " + quote(e) + " is not supported");
        }
    }
    loader.materials.assign(loader.model.materials.size(), NONE);
    loader.textures.assign(loader.model.textures.size(), {NONE, NONE});
    loader.nodes();
    if (loader.census.triangles == 0) {
        loader.fail("no triangles", loader.noTriangles());
    }
    return loader.extras;
}

}  // namespace photon
