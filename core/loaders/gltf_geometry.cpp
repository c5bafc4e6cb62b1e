// The glTF loader's geometry (gltf_loader.h): a primitive's attributes (plain, quantized, meshopt
// or Draco), its vertex order and its triangles (lists, strips, fans) in the world.
#include "core/loaders/gltf_loader.h"

namespace photon::gltf {

template <int N>
std::vector<glm::vec<N, float>> Loader::attribute(const View& v, int index, const std::string& name) const {
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

template <typename ViewOf>
void Loader::readAttributes(const tinygltf::Primitive& p, Mesh& mesh, const std::string& here, ViewOf viewOf) {
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

std::vector<std::uint32_t> Loader::vertexOrder(const tinygltf::Primitive& p, std::size_t vertices, const std::string& here) {
    if (p.indices >= 0) {
        return indices(p.indices, vertices, here);
    }
    std::vector<std::uint32_t> order(vertices);
    for (std::uint32_t i = 0; i < order.size(); ++i) {
        order[i] = i;
    }
    return order;
}

std::vector<std::uint32_t> Loader::dracoGeometry(const tinygltf::Primitive& p, const tinygltf::Value& ext, Mesh& mesh,
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

std::vector<glm::uvec3> Loader::assemble(int mode, const std::vector<std::uint32_t>& order) {
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

void Loader::primitive(const tinygltf::Primitive& p, const glm::mat4& transform, const std::string& here) {
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

std::string Loader::noTriangles() const {
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

}  // namespace photon::gltf
