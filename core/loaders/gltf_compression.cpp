#include "core/loaders/gltf_compression.h"

#include <cstring>
#include <limits>

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>
#include <meshoptimizer.h>

namespace photon {
namespace {

constexpr std::size_t kDecodedViewLimit = std::size_t(1) << 30;  // 1 GiB, as for model files

// The stride rules of the EXT_meshopt_compression specification, which are also the asserts of
// libmeshoptimizer's decoders (they vanish under NDEBUG and would read out of bounds).
void checkLayout(const MeshoptView& v) {
    auto stride = std::to_string(v.stride);
    switch (v.mode) {
        case MeshoptMode::Attributes:
            if (v.stride == 0 || v.stride > 256 || v.stride % 4 != 0) {
                throw DecodeError("ATTRIBUTES byteStride " + stride + " is not a multiple of 4 in [4, 256]");
            }
            break;
        case MeshoptMode::Triangles:
            if (v.count % 3 != 0) {
                throw DecodeError("TRIANGLES count " + std::to_string(v.count) + " is not a multiple of 3");
            }
            [[fallthrough]];
        case MeshoptMode::Indices:
            if (v.stride != 2 && v.stride != 4) {
                throw DecodeError("index byteStride " + stride + " is neither 2 nor 4");
            }
            break;
    }
    if (v.filter != MeshoptFilter::None && v.mode != MeshoptMode::Attributes) {
        throw DecodeError("filters apply to ATTRIBUTES only");
    }
    if ((v.filter == MeshoptFilter::Octahedral && v.stride != 4 && v.stride != 8) ||
        (v.filter == MeshoptFilter::Quaternion && v.stride != 8)) {
        throw DecodeError("byteStride " + stride + " does not suit the filter");
    }
}

}  // namespace

std::vector<unsigned char> decodeMeshopt(const MeshoptView& v, const unsigned char* data, std::size_t size) {
    checkLayout(v);
    if (v.count > kDecodedViewLimit / v.stride) {
        throw DecodeError("decodes to more than 1 GiB");
    }
    std::size_t bytes = v.count * v.stride;
    if (bytes / kMeshoptMaxRatio > size) {
        throw DecodeError(std::to_string(v.count) + " elements cannot come from " + std::to_string(size) +
                          " compressed bytes");
    }
    std::vector<unsigned char> out(bytes);
    int status = 0;
    switch (v.mode) {
        case MeshoptMode::Attributes:
            status = meshopt_decodeVertexBuffer(out.data(), v.count, v.stride, data, size);
            break;
        case MeshoptMode::Triangles:
            status = meshopt_decodeIndexBuffer(out.data(), v.count, v.stride, data, size);
            break;
        case MeshoptMode::Indices:
            status = meshopt_decodeIndexSequence(out.data(), v.count, v.stride, data, size);
            break;
    }
    if (status != 0) {
        throw DecodeError("not meshopt-compressed data (decoder status " + std::to_string(status) + ")");
    }
    switch (v.filter) {
        case MeshoptFilter::None: break;
        case MeshoptFilter::Octahedral: meshopt_decodeFilterOct(out.data(), v.count, v.stride); break;
        case MeshoptFilter::Quaternion: meshopt_decodeFilterQuat(out.data(), v.count, v.stride); break;
        case MeshoptFilter::Exponential: meshopt_decodeFilterExp(out.data(), v.count, v.stride); break;
    }
    return out;
}

// ---- Draco ----------------------------------------------------------------------------------------

DracoMesh::DracoMesh(const unsigned char* data, std::size_t size) {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data), size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) {
        throw DecodeError("not a Draco mesh: " + decoded.status().error_msg_string());
    }
    mesh_ = std::move(decoded).value();
    if (mesh_ == nullptr) {
        throw DecodeError("not a Draco mesh");
    }
}

DracoMesh::~DracoMesh() = default;

std::size_t DracoMesh::points() const { return mesh_->num_points(); }

std::vector<glm::uvec3> DracoMesh::triangles() const {
    std::vector<glm::uvec3> out(mesh_->num_faces());
    for (draco::FaceIndex f(0); f < mesh_->num_faces(); ++f) {
        const draco::Mesh::Face& face = mesh_->face(f);
        for (int c = 0; c < 3; ++c) {
            if (face[c].value() >= mesh_->num_points()) {
                throw DecodeError("face " + std::to_string(f.value()) + " names point " + std::to_string(face[c].value()) +
                                  " of " + std::to_string(mesh_->num_points()));
            }
            out[f.value()][c] = face[c].value();
        }
    }
    return out;
}

namespace {

template <typename T>
std::vector<unsigned char> convert(const draco::PointAttribute& a, std::size_t points, int components) {
    std::vector<unsigned char> out(points * sizeof(T) * std::size_t(components));
    T values[4] = {};
    for (draco::PointIndex p(0); p < points; ++p) {
        // The point-to-value map comes from the file too.
        if (!a.is_mapping_identity() && p.value() >= a.indices_map_size()) {
            throw DecodeError("attribute " + std::to_string(a.unique_id()) + " does not map every point");
        }
        draco::AttributeValueIndex v = a.mapped_index(p);
        if (v.value() >= a.size() || !a.ConvertValue<T>(v, std::int8_t(components), values)) {
            throw DecodeError("attribute " + std::to_string(a.unique_id()) + " has no value for point " +
                              std::to_string(p.value()));
        }
        std::memcpy(out.data() + std::size_t(p.value()) * sizeof(T) * std::size_t(components), values,
                    sizeof(T) * std::size_t(components));
    }
    return out;
}

}  // namespace

std::vector<unsigned char> DracoMesh::attribute(std::uint32_t id, int componentType, int components) const {
    const draco::PointAttribute* a = mesh_->GetAttributeByUniqueId(id);
    if (a == nullptr) {
        throw DecodeError("the Draco mesh has no attribute " + std::to_string(id));
    }
    if (components < 1 || components > 4 || a->num_components() < components) {
        throw DecodeError("attribute " + std::to_string(id) + " has " + std::to_string(a->num_components()) +
                          " components, the accessor " + std::to_string(components));
    }
    std::size_t n = points();
    switch (componentType) {
        case 5120: return convert<std::int8_t>(*a, n, components);
        case 5121: return convert<std::uint8_t>(*a, n, components);
        case 5122: return convert<std::int16_t>(*a, n, components);
        case 5123: return convert<std::uint16_t>(*a, n, components);
        case 5125: return convert<std::uint32_t>(*a, n, components);
        case 5126: return convert<float>(*a, n, components);
        default: throw DecodeError("component type " + std::to_string(componentType) + " is not one glTF has");
    }
}

}  // namespace photon
