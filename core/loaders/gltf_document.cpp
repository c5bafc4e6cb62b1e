#include "core/loaders/gltf_document.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>

#include <nlohmann/json.hpp>

#include "core/loaders/gltf_schema.h"
#include "core/system/error.h"

namespace photon {
namespace {

using json = nlohmann::json;

constexpr std::uint32_t kJsonChunk = 0x4E4F534Au;  // "JSON", little-endian

std::uint32_t word(const std::string& bytes, std::size_t at) {
    std::uint32_t w;
    std::memcpy(&w, bytes.data() + at, 4);
    return w;
}

void putWord(std::string& out, std::uint32_t w) { out.append(reinterpret_cast<const char*>(&w), 4); }

// glTF 1.0 says so in asset.version ("1.0", or the number 1), and keeps its objects in
// dictionaries where glTF 2.0 has arrays.
bool isGltf1(const json& root) {
    auto asset = root.find("asset");
    if (asset != root.end() && asset->is_object()) {
        auto version = asset->find("version");
        if (version != asset->end() && version->is_string()) {
            const std::string& v = version->get_ref<const std::string&>();
            return v == "1" || v.rfind("1.", 0) == 0;
        }
        if (version != asset->end() && version->is_number()) {
            return version->get<double>() >= 1.0 && version->get<double>() < 2.0;
        }
    }
    for (const char* key : {"meshes", "nodes", "accessors", "buffers"}) {
        auto it = root.find(key);
        if (it != root.end() && it->is_object()) {
            return true;
        }
    }
    return false;
}

bool uses(const json& root, const char* extension) {
    auto used = root.find("extensionsUsed");
    if (used == root.end() || !used->is_array()) {
        return false;
    }
    for (const json& e : *used) {
        if (e.is_string() && e.get_ref<const std::string&>() == extension) {
            return true;
        }
    }
    return false;
}

const json* extension(const json& object, const char* name) {
    if (!object.is_object()) {
        return nullptr;
    }
    auto extensions = object.find("extensions");
    if (extensions == object.end() || !extensions->is_object()) {
        return nullptr;
    }
    auto it = extensions->find(name);
    return it == extensions->end() ? nullptr : &*it;
}

// A fallback buffer stands for the decompressed views and has no bytes of its own: a one-byte
// data URI lets tinygltf parse it; the loader never reads it.
bool replaceFallbackBuffers(json& root, std::set<int>& fallbacks) {
    auto buffers = root.find("buffers");
    if (buffers == root.end() || !buffers->is_array()) {
        return false;
    }
    bool changed = false;
    for (std::size_t i = 0; i < buffers->size(); ++i) {
        json& b = (*buffers)[i];
        const json* meshopt = extension(b, "EXT_meshopt_compression");
        if (meshopt == nullptr || !meshopt->is_object() || b.contains("uri")) {
            continue;
        }
        auto fallback = meshopt->find("fallback");
        if (fallback == meshopt->end() || !fallback->is_boolean() || !fallback->get<bool>()) {
            continue;
        }
        b["byteLength"] = 1;
        b["uri"] = "data:application/octet-stream;base64,AA==";
        fallbacks.insert(int(i));
        changed = true;
    }
    return changed;
}

// A Draco primitive's faces come from its compressed buffer view: its "indices" accessor only
// describes them (and may have no buffer view, which tinygltf refuses).
bool dropDracoIndices(json& root) {
    auto meshes = root.find("meshes");
    if (meshes == root.end() || !meshes->is_array()) {
        return false;
    }
    bool changed = false;
    for (json& mesh : *meshes) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) {
            continue;
        }
        for (json& p : mesh["primitives"]) {
            if (extension(p, "KHR_draco_mesh_compression") != nullptr && p.is_object() && p.contains("indices")) {
                p.erase("indices");
                changed = true;
            }
        }
    }
    return changed;
}

// ---- The files and data that buffers and images name --------------------------------------------

bool startsWithNoCase(const std::string& text, const std::string& prefix) {
    if (text.size() < prefix.size()) {
        return false;
    }
    for (std::size_t i = 0; i < prefix.size(); ++i) {
        if (std::tolower(static_cast<unsigned char>(text[i])) != prefix[i]) {
            return false;
        }
    }
    return true;
}

// A URI that names something outside the model's folder tree: one with a scheme (RFC 3986's
// [A-Za-z][A-Za-z0-9+.-]*: — "http:", "file:", and a Windows drive letter "C:", which reads as
// one), or an absolute path. A relative URI with a colon in its first segment is written "./a:b".
bool absoluteOrRemote(const std::string& uri) {
    if (!uri.empty() && (uri[0] == '/' || uri[0] == '\\')) {
        return true;
    }
    if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) {
        return false;
    }
    for (char c : uri) {
        if (c == ':') {
            return true;
        }
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') {
            return false;
        }
    }
    return false;
}

int base64Digit(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : c == '/' ? 63 : -1;
}

// A data URI as glTF 2.0 allows it: data:[<mediatype>][;<parameter>]*;base64,<base64>. Gives the
// reason it is not one (or "") and, when it is, where its base64 begins and how many bytes it holds.
std::string dataUriProblem(const std::string& uri, std::size_t& payload, std::size_t& length) {
    std::size_t comma = uri.find(',');
    if (comma == std::string::npos || comma < 12 || !startsWithNoCase(uri.substr(comma - 7, 7), ";base64")) {
        return "a data URI must be base64 (data:...;base64,...)";
    }
    payload = comma + 1;
    std::size_t end = uri.size();
    std::size_t padding = 0;
    while (end > payload && uri[end - 1] == '=' && padding < 2) {
        end -= 1;
        padding += 1;
    }
    for (std::size_t i = payload; i < end; ++i) {
        if (base64Digit(uri[i]) < 0) {
            return "the data URI's base64 has a bad character '" + printable(uri.substr(i, 1)) + "' at byte " + std::to_string(i);
        }
    }
    std::size_t digits = end - payload;
    if (digits % 4 == 1 || (padding > 0 && (digits + padding) % 4 != 0)) {
        return "the data URI's base64 ends in the middle of a byte";
    }
    length = digits / 4 * 3 + (digits % 4 == 0 ? 0 : digits % 4 - 1);  // 2 digits: 1 byte, 3: 2
    return length == 0 ? "the data URI holds no bytes" : "";
}

// The data URIs tinygltf decodes: these media types exactly, and a buffer's of exactly byteLength
// bytes. Any other good one is given to it as application/octet-stream, cut to byteLength.
bool tinygltfDecodes(const std::string& uri) {
    for (const char* type : {"application/octet-stream", "application/gltf-buffer", "image/jpeg", "image/png",
                             "image/bmp", "image/gif", "text/plain"}) {
        if (uri.rfind(std::string("data:") + type + ";base64,", 0) == 0) {
            return true;
        }
    }
    return false;
}

// Every buffer's and image's uri: a data URI checked here, whole (tinygltf's own message about a
// bad one quotes all of it, megabytes on one line), or a file relative to the model's folder.
// Returns whether a data URI was rewritten for tinygltf.
bool checkUris(const std::string& path, json& root, const char* array) {
    auto objects = root.find(array);
    if (objects == root.end()) {
        return false;
    }
    bool changed = false;
    for (std::size_t i = 0; i < objects->size(); ++i) {
        json& object = (*objects)[i];
        auto uri = object.find("uri");
        if (uri == object.end()) {
            continue;
        }
        const std::string& text = uri->get_ref<const std::string&>();
        std::string where = path + ": /" + array + "/" + std::to_string(i) + "/uri: ";
        if (!startsWithNoCase(text, "data:")) {
            if (absoluteOrRemote(text)) {
                throw InputError(where + quote(printable(text.substr(0, 4 * kQuotedTokenMax))) +
                                 ": absolute and remote URIs are not read; name a file relative to the model's folder");
            }
            continue;
        }
        std::size_t payload = 0;
        std::size_t length = 0;
        std::string problem = dataUriProblem(text, payload, length);
        if (!problem.empty()) {
            throw InputError(where + problem);
        }
        std::uint64_t byteLength = length;
        auto declared = object.find("byteLength");  // a non-negative integer (gltf_schema.cpp)
        if (std::strcmp(array, "buffers") == 0 && declared != object.end()) {
            byteLength = declared->get<std::uint64_t>();
            if (length < byteLength) {
                throw InputError(where + "the data URI holds " + std::to_string(length) + " bytes, byteLength says " +
                                 std::to_string(byteLength));
            }
        }
        if (!tinygltfDecodes(text) || byteLength < length) {
            std::size_t digits = std::size_t((byteLength * 4 + 2) / 3);  // byteLength bytes' digits, unpadded
            *uri = "data:application/octet-stream;base64," + text.substr(payload, digits);
            changed = true;
        }
    }
    return changed;
}

// The GLB container again around new JSON, with the chunks after the JSON chunk as they were.
std::string rebuildGlb(const std::string& bytes, std::size_t jsonEnd, std::string text) {
    while (text.size() % 4 != 0) {
        text += ' ';
    }
    std::string rest = bytes.substr(std::min(jsonEnd, bytes.size()));
    std::string out;
    putWord(out, word(bytes, 0));
    putWord(out, 2);
    putWord(out, std::uint32_t(12 + 8 + text.size() + rest.size()));
    putWord(out, std::uint32_t(text.size()));
    putWord(out, kJsonChunk);
    return out + text + rest;
}

}  // namespace

GltfDocument prepareGltf(const std::string& path, const std::string& bytes) {
    GltfDocument doc;
    doc.bytes = bytes;
    doc.binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
    if (bytes.empty()) {
        throw InputError(path + ": empty file");  // tinygltf: "JSON string too short."
    }
    bool glbName = path.size() >= 4 && startsWithNoCase(path.substr(path.size() - 4), ".glb");
    if (bytes.size() < 20 && (doc.binary || (glbName && std::string("glTF").rfind(bytes, 0) == 0))) {
        throw InputError(path + ": a binary glTF (.glb) shorter than its 20-byte header");
    }
    std::string text = bytes;
    std::size_t jsonEnd = 0;
    if (doc.binary) {
        std::uint32_t version = word(bytes, 4);
        if (version == 1) {
            throw InputError(path + ": a glTF 1.0 binary file; Photon reads glTF 2.0");
        }
        if (version != 2) {
            throw InputError(path + ": glTF binary version " + std::to_string(version) + "; Photon reads version 2");
        }
        std::uint32_t length = word(bytes, 12);
        if (word(bytes, 16) != kJsonChunk || length > bytes.size() - 20) {
            return doc;
        }
        text = bytes.substr(20, length);
        jsonEnd = 20 + std::size_t(length);
        // tinygltf 2.7 checks the binary chunk against the file's length without the chunk's own
        // 8-byte header, so a chunk that claims to end the file is read 8 bytes past its end.
        if (jsonEnd + 8 <= bytes.size() && jsonEnd + 8 + std::size_t(word(bytes, jsonEnd)) > bytes.size()) {
            throw InputError(path + ": the binary chunk of " + std::to_string(word(bytes, jsonEnd)) +
                             " bytes extends beyond the file");
        }
    }
    json root = json::parse(text, nullptr, false);
    if (root.is_discarded() || !root.is_object()) {
        return doc;  // tinygltf reports the JSON error with its place
    }
    if (isGltf1(root)) {
        throw InputError(path + ": a glTF 1.0 file; Photon reads glTF 2.0");
    }
    checkGltfTypes(path, root);
    bool changed = checkUris(path, root, "buffers");
    changed |= checkUris(path, root, "images");
    if (uses(root, "EXT_meshopt_compression")) {
        changed |= replaceFallbackBuffers(root, doc.fallbackBuffers);
    }
    if (uses(root, "KHR_draco_mesh_compression")) {
        changed |= dropDracoIndices(root);
    }
    if (changed) {
        std::string rewritten = root.dump(-1, ' ', false, json::error_handler_t::replace);
        doc.bytes = doc.binary ? rebuildGlb(bytes, jsonEnd, std::move(rewritten)) : std::move(rewritten);
    }
    return doc;
}

}  // namespace photon
