#include "glb_writer.h"

#include <cstdint>
#include <cstring>

#include <nlohmann/json.hpp>

namespace photon::tools {
namespace {

void append(std::string& out, const void* data, std::size_t bytes) { out.append(static_cast<const char*>(data), bytes); }

void appendU32(std::string& out, std::uint32_t x) { append(out, &x, 4); }

}  // namespace

std::string glbFromMesh(const Mesh& mesh, const std::string& material) {
    std::string bin;
    append(bin, mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
    std::size_t normalsAt = bin.size();
    append(bin, mesh.normals.data(), mesh.normals.size() * sizeof(glm::vec3));
    std::size_t indicesAt = bin.size();
    append(bin, mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3));
    while (bin.size() % 4 != 0) {
        bin.push_back('\0');
    }
    glm::vec3 lo(1e30f);
    glm::vec3 hi(-1e30f);
    for (glm::vec3 p : mesh.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    using nlohmann::json;
    json doc = {
        {"asset", {{"version", "2.0"}, {"generator", "photon tools/glb_writer"}}},
        {"scene", 0},
        {"scenes", json::array({{{"nodes", json::array({0})}}})},
        {"nodes", json::array({{{"mesh", 0}}})},
        {"materials", json::array({json::parse(material)})},
        {"buffers", json::array({{{"byteLength", bin.size()}}})},
        {"bufferViews", json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", normalsAt}},
                                     {{"buffer", 0}, {"byteOffset", normalsAt}, {"byteLength", indicesAt - normalsAt}},
                                     {{"buffer", 0}, {"byteOffset", indicesAt},
                                      {"byteLength", mesh.triangles.size() * sizeof(glm::uvec3)}}})},
        {"accessors", json::array({{{"bufferView", 0}, {"componentType", 5126}, {"count", mesh.positions.size()},
                                    {"type", "VEC3"}, {"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}},
                                   {{"bufferView", 2}, {"componentType", 5125}, {"count", 3 * mesh.triangles.size()},
                                    {"type", "SCALAR"}}})},
    };
    json primitive = {{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}};
    if (!mesh.normals.empty()) {
        doc["accessors"].push_back({{"bufferView", 1}, {"componentType", 5126}, {"count", mesh.normals.size()}, {"type", "VEC3"}});
        primitive["attributes"]["NORMAL"] = 2;
    }
    doc["meshes"] = json::array({{{"primitives", json::array({primitive})}}});
    std::string text = doc.dump();
    while (text.size() % 4 != 0) {
        text.push_back(' ');
    }
    std::string glb;
    appendU32(glb, 0x46546C67u);  // "glTF"
    appendU32(glb, 2);
    appendU32(glb, std::uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    appendU32(glb, std::uint32_t(text.size()));
    appendU32(glb, 0x4E4F534Au);  // "JSON"
    glb += text;
    appendU32(glb, std::uint32_t(bin.size()));
    appendU32(glb, 0x004E4942u);  // "BIN\0"
    glb += bin;
    return glb;
}

}  // namespace photon::tools
