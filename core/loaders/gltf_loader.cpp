// glTF 2.0, .gltf (external or data-URI buffers) and .glb (tinygltf): the default scene's node
// hierarchy with its transforms, indexed triangles (lists, strips, fans), normals, texture
// coordinates, the metallic-roughness material with its textures and extensions, cameras and
// KHR_lights_punctual. tinygltf parses the JSON and gathers the buffers and images; every
// accessor, index and node is checked here. This file holds the buffers, their views and
// accessors, the node walk and the entry; materials and geometry have files of their own
// (gltf_loader.h).
#include "core/loaders/gltf_loader.h"

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

}  // namespace

namespace gltf {

Loader::Bytes Loader::slice(int buffer, std::size_t offset, std::size_t length, const std::string& where) const {
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

Loader::Bytes Loader::bufferView(int index, const std::string& where) {
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

Loader::Bytes Loader::decompressed(std::size_t index, const tinygltf::Value& ext, const std::string& here) {
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

const tinygltf::Accessor& Loader::accessor(int index, const std::string& where) const {
    if (index < 0 || std::size_t(index) >= model.accessors.size()) {
        fail(where, "accessor " + std::to_string(index) + " does not exist");
    }
    const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
    if (a.sparse.isSparse) {
        fail(at("accessors", std::size_t(index)), "sparse accessors are not supported");
    }
    return a;
}

Loader::View Loader::layout(int index, Bytes bytes, std::size_t offset, std::size_t byteStride, const std::string& viewWhere) const {
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

Loader::View Loader::view(int index, const std::string& where) {
    const tinygltf::Accessor& a = accessor(index, where);
    if (a.bufferView < 0 || std::size_t(a.bufferView) >= model.bufferViews.size()) {
        fail(at("accessors", std::size_t(index)), "no buffer view (bufferView " + std::to_string(a.bufferView) + ")");
    }
    Bytes bytes = bufferView(a.bufferView, at("accessors", std::size_t(index)));
    return layout(index, bytes, a.byteOffset, model.bufferViews[std::size_t(a.bufferView)].byteStride,
                  at("bufferViews", std::size_t(a.bufferView)));
}

float Loader::component(const unsigned char* e, int type, bool normalized) {
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

bool Loader::allowedType(const std::string& attribute, int type, bool normalized) {
    if (type == TINYGLTF_COMPONENT_TYPE_FLOAT) {
        return true;
    }
    if (attribute == "NORMAL" || attribute == "TANGENT") {
        return normalized && (type == TINYGLTF_COMPONENT_TYPE_BYTE || type == TINYGLTF_COMPONENT_TYPE_SHORT);
    }
    return type == TINYGLTF_COMPONENT_TYPE_BYTE || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
           type == TINYGLTF_COMPONENT_TYPE_SHORT || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
}

std::vector<std::uint32_t> Loader::indices(int index, std::size_t vertices, const std::string& where) {
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

glm::mat4 Loader::localTransform(const tinygltf::Node& n) {
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

void Loader::camera(int index, const glm::mat4& world, const std::string& here) {
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

void Loader::light(const tinygltf::Node& node, const glm::mat4& world, const std::string& here) {
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

void Loader::nodes() {
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

}  // namespace gltf

namespace {

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
    gltf::Loader loader{scene, path, options, read, {}, {}, {}, NONE, {}, {}, {}, 0, {}};
    if (bytes.size() > 0xffffffffu) {
        throw InputError(path + ": larger than 4 GiB");
    }
    GltfDocument doc = prepareGltf(path, bytes);
    loader.fallbackBuffers = doc.fallbackBuffers;
    tinygltf::TinyGLTF parser;
    FileSystem fs{read, path, options.paths, {}};
    parser.SetFsCallbacks({fileExists, expandPath, readWholeFile, writeWholeFile, &fs});
    parser.SetImageLoader(keepImage, &loader.model);
    std::string err;
    std::string warn;
    std::string folder = folderOf(path);
    std::string base = folder.empty() ? "." : folder;
    const std::string& data = doc.bytes;
    bool ok = doc.binary ? parser.LoadBinaryFromMemory(&loader.model, &err, &warn,
                                                     reinterpret_cast<const unsigned char*>(data.data()),
                                                     unsigned(data.size()), base)
                         : parser.LoadASCIIFromString(&loader.model, &err, &warn, data.data(), unsigned(data.size()), base);
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
