#include "core/loaders/gltf_schema.h"

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/loaders/json_node.h"
#include "core/system/error.h"

namespace photon {
namespace {

using json = nlohmann::json;

// What a property's value must be. The plural kinds are arrays whose every element is the singular
// kind; an Id is a glTFid or a count (a non-negative integer).
enum class Kind { Any, Object, Objects, String, Strings, Number, Numbers, Boolean, Id, Ids, IdMap, IdMaps };

struct Type;

struct Property {
    const char* name;
    Kind kind;
    const Type* type = nullptr;  // Object and Objects: the object's own type (nullptr: any object)
};

struct Extension {
    const char* name;
    const Type* type;
};

// A kind of glTF object: its properties besides name, extensions and extras (which every object
// has: a string, an object of objects, anything), and the extensions the loader reads on it.
struct Type {
    std::vector<Property> properties;
    std::vector<Extension> extensions;
};

// ---- The glTF 2.0 schema, leaves first ------------------------------------------------------------

// Extensions (the fields the loader reads).
const Type kTextureTransform{{{"offset", Kind::Numbers}, {"rotation", Kind::Number}, {"scale", Kind::Numbers},
                              {"texCoord", Kind::Id}}, {}};
const Type kTextureInfo{{{"index", Kind::Id}, {"texCoord", Kind::Id}}, {{"KHR_texture_transform", &kTextureTransform}}};
const Type kNormalTextureInfo{{{"index", Kind::Id}, {"texCoord", Kind::Id}, {"scale", Kind::Number}},
                              {{"KHR_texture_transform", &kTextureTransform}}};
const Type kOcclusionTextureInfo{{{"index", Kind::Id}, {"texCoord", Kind::Id}, {"strength", Kind::Number}},
                                 {{"KHR_texture_transform", &kTextureTransform}}};
const Type kTransmission{{{"transmissionFactor", Kind::Number}, {"transmissionTexture", Kind::Object, &kTextureInfo}}, {}};
const Type kIor{{{"ior", Kind::Number}}, {}};
const Type kEmissiveStrength{{{"emissiveStrength", Kind::Number}}, {}};
const Type kVolume{{{"thicknessFactor", Kind::Number}, {"thicknessTexture", Kind::Object, &kTextureInfo},
                    {"attenuationDistance", Kind::Number}, {"attenuationColor", Kind::Numbers}}, {}};
const Type kVolumeScatter{{{"multiscatterColor", Kind::Numbers}, {"scatterAnisotropy", Kind::Number}}, {}};
// KHR_materials_dispersion's one number is checked by the loader, type and range in one message.
const Type kSpot{{{"innerConeAngle", Kind::Number}, {"outerConeAngle", Kind::Number}}, {}};
const Type kLight{{{"type", Kind::String}, {"color", Kind::Numbers}, {"intensity", Kind::Number}, {"range", Kind::Number},
                   {"spot", Kind::Object, &kSpot}}, {}};
const Type kLights{{{"lights", Kind::Objects, &kLight}}, {}};
const Type kNodeLight{{{"light", Kind::Id}}, {}};

// The core specification's objects.
const Type kAsset{{{"copyright", Kind::String}, {"generator", Kind::String}, {"version", Kind::String},
                   {"minVersion", Kind::String}}, {}};
const Type kScene{{{"nodes", Kind::Ids}}, {}};
const Type kNode{{{"camera", Kind::Id}, {"children", Kind::Ids}, {"skin", Kind::Id}, {"matrix", Kind::Numbers},
                  {"mesh", Kind::Id}, {"rotation", Kind::Numbers}, {"scale", Kind::Numbers},
                  {"translation", Kind::Numbers}, {"weights", Kind::Numbers}},
                 {{"KHR_lights_punctual", &kNodeLight}}};
const Type kPrimitive{{{"attributes", Kind::IdMap}, {"indices", Kind::Id}, {"material", Kind::Id}, {"mode", Kind::Id},
                       {"targets", Kind::IdMaps}}, {}};
const Type kMesh{{{"primitives", Kind::Objects, &kPrimitive}, {"weights", Kind::Numbers}}, {}};
const Type kPbrMetallicRoughness{{{"baseColorFactor", Kind::Numbers}, {"baseColorTexture", Kind::Object, &kTextureInfo},
                                  {"metallicFactor", Kind::Number}, {"roughnessFactor", Kind::Number},
                                  {"metallicRoughnessTexture", Kind::Object, &kTextureInfo}}, {}};
const Type kMaterial{{{"pbrMetallicRoughness", Kind::Object, &kPbrMetallicRoughness},
                      {"normalTexture", Kind::Object, &kNormalTextureInfo},
                      {"occlusionTexture", Kind::Object, &kOcclusionTextureInfo},
                      {"emissiveTexture", Kind::Object, &kTextureInfo}, {"emissiveFactor", Kind::Numbers},
                      {"alphaMode", Kind::String}, {"alphaCutoff", Kind::Number}, {"doubleSided", Kind::Boolean}},
                     {{"KHR_materials_transmission", &kTransmission}, {"KHR_materials_ior", &kIor},
                      {"KHR_materials_emissive_strength", &kEmissiveStrength}, {"KHR_materials_volume", &kVolume},
                      {"KHR_materials_volume_scatter", &kVolumeScatter}}};
const Type kTexture{{{"sampler", Kind::Id}, {"source", Kind::Id}}, {}};
const Type kImage{{{"uri", Kind::String}, {"mimeType", Kind::String}, {"bufferView", Kind::Id}}, {}};
const Type kSampler{{{"magFilter", Kind::Id}, {"minFilter", Kind::Id}, {"wrapS", Kind::Id}, {"wrapT", Kind::Id}}, {}};
const Type kSparseIndices{{{"bufferView", Kind::Id}, {"byteOffset", Kind::Id}, {"componentType", Kind::Id}}, {}};
const Type kSparseValues{{{"bufferView", Kind::Id}, {"byteOffset", Kind::Id}}, {}};
const Type kSparse{{{"count", Kind::Id}, {"indices", Kind::Object, &kSparseIndices},
                    {"values", Kind::Object, &kSparseValues}}, {}};
const Type kAccessor{{{"bufferView", Kind::Id}, {"byteOffset", Kind::Id}, {"componentType", Kind::Id},
                      {"normalized", Kind::Boolean}, {"count", Kind::Id}, {"type", Kind::String},
                      {"max", Kind::Numbers}, {"min", Kind::Numbers}, {"sparse", Kind::Object, &kSparse}}, {}};
const Type kBufferView{{{"buffer", Kind::Id}, {"byteOffset", Kind::Id}, {"byteLength", Kind::Id},
                        {"byteStride", Kind::Id}, {"target", Kind::Id}}, {}};
const Type kBuffer{{{"uri", Kind::String}, {"byteLength", Kind::Id}}, {}};
const Type kOrthographic{{{"xmag", Kind::Number}, {"ymag", Kind::Number}, {"zfar", Kind::Number},
                          {"znear", Kind::Number}}, {}};
const Type kPerspective{{{"aspectRatio", Kind::Number}, {"yfov", Kind::Number}, {"zfar", Kind::Number},
                         {"znear", Kind::Number}}, {}};
const Type kCamera{{{"orthographic", Kind::Object, &kOrthographic}, {"perspective", Kind::Object, &kPerspective},
                    {"type", Kind::String}}, {}};
const Type kSkin{{{"inverseBindMatrices", Kind::Id}, {"skeleton", Kind::Id}, {"joints", Kind::Ids}}, {}};
const Type kChannelTarget{{{"node", Kind::Id}, {"path", Kind::String}}, {}};
const Type kChannel{{{"sampler", Kind::Id}, {"target", Kind::Object, &kChannelTarget}}, {}};
const Type kAnimationSampler{{{"input", Kind::Id}, {"interpolation", Kind::String}, {"output", Kind::Id}}, {}};
const Type kAnimation{{{"channels", Kind::Objects, &kChannel}, {"samplers", Kind::Objects, &kAnimationSampler}}, {}};
const Type kGltf{{{"extensionsUsed", Kind::Strings}, {"extensionsRequired", Kind::Strings},
                  {"accessors", Kind::Objects, &kAccessor}, {"animations", Kind::Objects, &kAnimation},
                  {"asset", Kind::Object, &kAsset}, {"buffers", Kind::Objects, &kBuffer},
                  {"bufferViews", Kind::Objects, &kBufferView}, {"cameras", Kind::Objects, &kCamera},
                  {"images", Kind::Objects, &kImage}, {"materials", Kind::Objects, &kMaterial},
                  {"meshes", Kind::Objects, &kMesh}, {"nodes", Kind::Objects, &kNode},
                  {"samplers", Kind::Objects, &kSampler}, {"scene", Kind::Id}, {"scenes", Kind::Objects, &kScene},
                  {"skins", Kind::Objects, &kSkin}, {"textures", Kind::Objects, &kTexture}},
                 {{"KHR_lights_punctual", &kLights}}};

// ---- The check ------------------------------------------------------------------------------------

// The element kind of an array kind, or Kind::Any for a kind that is not an array.
Kind elementOf(Kind kind) {
    switch (kind) {
        case Kind::Objects: return Kind::Object;
        case Kind::Strings: return Kind::String;
        case Kind::Numbers: return Kind::Number;
        case Kind::Ids: return Kind::Id;
        case Kind::IdMaps: return Kind::IdMap;
        default: return Kind::Any;
    }
}

// What a value must be, as the message says it.
const char* expected(Kind kind) {
    switch (kind) {
        case Kind::Object: case Kind::IdMap: return "an object";
        case Kind::String: return "a string";
        case Kind::Number: return "a number";
        case Kind::Boolean: return "a boolean";
        case Kind::Id: return "a non-negative integer";
        default: return "an array";
    }
}

// A non-negative integer written as one: tinygltf passes over 3.0 as over a string.
bool isId(const json& v) {
    return v.is_number_unsigned() || (v.is_number_integer() && v.get<std::int64_t>() >= 0);
}

bool has(const json& v, Kind kind) {
    switch (kind) {
        case Kind::Any: return true;
        case Kind::Object: case Kind::IdMap: return v.is_object();
        case Kind::String: return v.is_string();
        case Kind::Number: return v.is_number();
        case Kind::Boolean: return v.is_boolean();
        case Kind::Id: return isId(v);
        default: return v.is_array();
    }
}

// The value as the message names it: its JSON type, or a number itself where the type was right.
std::string describe(const json& v) {
    switch (v.type()) {
        case json::value_t::object: return "an object";
        case json::value_t::array: return "an array";
        case json::value_t::string: return "a string";
        case json::value_t::boolean: return "a boolean";
        case json::value_t::null: return "null";
        default: return v.dump();  // a number: at most a few dozen characters
    }
}

// A name from the file as a JSON pointer's token (json_node.h), printable and cut as quote() cuts.
std::string keyToken(const std::string& key) {
    std::string shown = printable(pointerToken(key.substr(0, 4 * kQuotedTokenMax)));
    if (shown.size() <= kQuotedTokenMax) {
        return shown;
    }
    std::string quoted = quote(shown);  // 'cut...'
    return quoted.substr(1, quoted.size() - 2);
}

struct Checker {
    const std::string& path;

    [[noreturn]] void refuse(const std::string& where, Kind kind, const json& v) const {
        std::string is = describe(v);
        if (kind != Kind::Id && v.is_number()) {
            is = "a number";
        }
        throw InputError(path + ": " + where + ": must be " + expected(kind) + ", not " + is);
    }

    void value(const json& v, Kind kind, const Type* type, const std::string& where) const {
        if (!has(v, kind)) {
            refuse(where, kind, v);
        }
        if (kind == Kind::Object && type != nullptr) {
            object(v, *type, where);
        } else if (kind == Kind::IdMap) {
            for (const auto& [key, id] : v.items()) {
                value(id, Kind::Id, nullptr, where + "/" + keyToken(key));
            }
        } else if (elementOf(kind) != Kind::Any) {
            for (std::size_t i = 0; i < v.size(); ++i) {
                value(v[i], elementOf(kind), type, where + "/" + std::to_string(i));
            }
        }
    }

    void object(const json& v, const Type& type, const std::string& where) const {
        for (const Property& p : type.properties) {
            auto it = v.find(p.name);
            if (it != v.end()) {
                value(*it, p.kind, p.type, where + "/" + p.name);
            }
        }
        auto name = v.find("name");
        if (name != v.end()) {
            value(*name, Kind::String, nullptr, where + "/name");
        }
        auto extensions = v.find("extensions");
        if (extensions == v.end()) {
            return;
        }
        value(*extensions, Kind::Object, nullptr, where + "/extensions");
        for (const auto& [key, extension] : extensions->items()) {
            std::string here = where + "/extensions/" + keyToken(key);
            value(extension, Kind::Object, nullptr, here);
            for (const Extension& known : type.extensions) {
                if (key == known.name) {
                    object(extension, *known.type, here);
                }
            }
        }
    }
};

}  // namespace

void checkGltfTypes(const std::string& path, const json& root) {
    Checker{path}.object(root, kGltf, "");
}

}  // namespace photon
