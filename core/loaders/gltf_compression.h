// The compressed forms of glTF geometry that Photon decodes before it reads an accessor:
// EXT_meshopt_compression buffer views (libmeshoptimizer) and KHR_draco_mesh_compression
// primitives (libdraco). Every count, stride and size comes from a file that may be hostile, so
// each is checked against the decoders' own limits and the real bytes before a decoder runs; a
// failure is a DecodeError with the reason, to which the glTF loader adds the file and the JSON
// pointer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace draco {
class Mesh;
}

namespace photon {

struct DecodeError : std::runtime_error {
    explicit DecodeError(const std::string& what) : std::runtime_error(what) {}
};

// ---- EXT_meshopt_compression ---------------------------------------------------------------------

enum class MeshoptMode { Attributes, Triangles, Indices };
enum class MeshoptFilter { None, Octahedral, Quaternion, Exponential };

// One compressed buffer view: `count` elements of `stride` bytes once decoded.
struct MeshoptView {
    std::size_t count = 0;
    std::size_t stride = 0;
    MeshoptMode mode = MeshoptMode::Attributes;
    MeshoptFilter filter = MeshoptFilter::None;
};

// The most decoded bytes one compressed byte may stand for. meshopt's densest code, a vertex
// byte lane that never changes, spends 2 header bits on 16 bytes (64 : 1); index codes spend at
// least a byte a triangle. A file that claims more is refused before anything is allocated.
inline constexpr std::size_t kMeshoptMaxRatio = 128;

// The count × stride bytes of a compressed view, decoded and unfiltered.
std::vector<unsigned char> decodeMeshopt(const MeshoptView& view, const unsigned char* data, std::size_t size);

// ---- KHR_draco_mesh_compression ------------------------------------------------------------------

// A decoded Draco mesh: its triangles, and each attribute (by the unique id the glTF extension
// names) converted to an accessor's component type.
class DracoMesh {
public:
    DracoMesh(const unsigned char* data, std::size_t size);
    ~DracoMesh();
    DracoMesh(const DracoMesh&) = delete;
    DracoMesh& operator=(const DracoMesh&) = delete;

    std::size_t points() const;
    // Every face, each index checked to be a point.
    std::vector<glm::uvec3> triangles() const;
    // Attribute `id`'s value at every point as `components` values of the glTF component type
    // `componentType` (5120 BYTE … 5126 FLOAT), tightly packed: the bytes an accessor would read.
    std::vector<unsigned char> attribute(std::uint32_t id, int componentType, int components) const;

private:
    std::unique_ptr<draco::Mesh> mesh_;
};

}  // namespace photon
