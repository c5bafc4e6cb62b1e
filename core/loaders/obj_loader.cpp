// Wavefront OBJ and MTL (tinyobjloader). The text is checked line by line first, so that an index
// out of range or a number that is not finite is reported with its line; tinyobjloader then
// parses it and triangulates polygons.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <unordered_map>

#include <tiny_obj_loader.h>

#include "core/loaders/model_loader.h"
#include "core/loaders/texture_loader.h"
#include "core/system/error.h"
#include "shared/math.h"

namespace photon {
namespace {

// The next whitespace-separated token of a line.
bool nextToken(const std::string& line, std::size_t& at, std::string& token) {
    at = line.find_first_not_of(" \t\r", at);
    if (at == std::string::npos) {
        return false;
    }
    std::size_t end = line.find_first_of(" \t\r", at);
    token = line.substr(at, end == std::string::npos ? std::string::npos : end - at);
    at = end == std::string::npos ? line.size() : end;
    return true;
}

// The line-by-line check: vertex numbers finite, every face index within the vertices, texture
// coordinates and normals defined so far (OBJ indices count from 1; negative ones count back).
void checkObjText(const std::string& path, const std::string& text) {
    std::size_t counts[3] = {0, 0, 0};  // v, vt, vn
    std::size_t lineNumber = 0;
    for (std::size_t start = 0; start < text.size();) {
        std::size_t end = text.find('\n', start);
        std::string line = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
        start = end == std::string::npos ? text.size() : end + 1;
        lineNumber += 1;
        if (line.find('\0') != std::string::npos) {
            throw InputError(path + ": line " + std::to_string(lineNumber) + ": a NUL byte: not a text file");
        }
        std::size_t at = 0;
        std::string keyword;
        if (!nextToken(line, at, keyword) || keyword[0] == '#') {
            continue;
        }
        auto fail = [&](const std::string& reason) {
            throw InputError(path + ": line " + std::to_string(lineNumber) + ": " + reason);
        };
        int kind = keyword == "v" ? 0 : keyword == "vt" ? 1 : keyword == "vn" ? 2 : -1;
        if (kind >= 0) {
            std::string token;
            int numbers = 0;
            while (nextToken(line, at, token) && numbers < 3) {
                char* stop = nullptr;
                double x = std::strtod(token.c_str(), &stop);
                if (stop != token.c_str() + token.size() || !std::isfinite(x) || std::abs(x) > 3.4e38) {
                    fail(quote(token) + " is not a finite number");
                }
                numbers += 1;
            }
            int needed = kind == 1 ? 2 : 3;
            if (numbers < needed) {
                fail(keyword + " needs " + std::to_string(needed) + " numbers");
            }
            counts[kind] += 1;
        } else if (keyword == "f") {
            std::string token;
            int corners = 0;
            while (nextToken(line, at, token)) {
                corners += 1;
                std::size_t slash = 0;
                for (int part = 0; part < 3 && slash != std::string::npos; ++part) {
                    std::size_t next = token.find('/', slash);
                    std::string index = token.substr(slash, next == std::string::npos ? std::string::npos : next - slash);
                    slash = next == std::string::npos ? next : next + 1;
                    if (index.empty()) {
                        if (part == 0) {
                            fail("face corner " + quote(token) + " has no vertex index");
                        }
                        continue;
                    }
                    char* stop = nullptr;
                    long long i = std::strtoll(index.c_str(), &stop, 10);
                    const char* names[3] = {"vertex", "texture coordinate", "normal"};
                    long long n = static_cast<long long>(counts[part]);
                    if (stop != index.c_str() + index.size() || i == 0 || i > n || i < -n) {
                        fail(std::string(names[part]) + " index " + quote(index) + " out of range (" +
                             std::to_string(n) + " defined before this line)");
                    }
                }
            }
            if (corners < 3) {
                fail("a face needs 3 corners or more");
            }
        }
    }
}

// A UTF-8 byte order mark (Windows editors write one) is not part of the first line.
std::string withoutBom(std::string text) {
    if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) {
        text.erase(0, 3);
    }
    return text;
}

// tinyobjloader reads `\` in an mtllib line as an escape (of a space in a name), so that
// `mtllib sub\ok.mtl`, as Windows exporters write it, would name "subok.mtl": a `\` before
// anything but a space becomes the separator `/` (namedFile reads `\` as one elsewhere).
void mtllibSeparators(std::string& text) {
    for (std::size_t line = 0; line < text.size();) {
        std::size_t end = std::min(text.find('\n', line), text.size());
        std::size_t start = text.find_first_not_of(" \t", line);
        if (start < end && text.compare(start, 7, "mtllib ") == 0) {
            for (std::size_t i = start; i + 1 < end; ++i) {
                if (text[i] == '\\' && text[i + 1] != ' ') {
                    text[i] = '/';
                }
            }
        }
        line = end + 1;
    }
}

// MTL files through the loader's file reader, relative to the OBJ file and inside its folder tree.
class MtlReader final : public tinyobj::MaterialReader {
public:
    MtlReader(const std::string& objPath, const FileReader& read, const PathPolicy& paths)
        : objPath_(objPath), read_(read), paths_(paths) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* map, std::string* warn, std::string* err) override {
        std::string path = namedFile(folderOf(objPath_), name);
        checkNamedFile(objPath_, path, "mtllib", paths_);
        std::string text = withoutBom(read_(path, "MTL file"));  // throws InputError naming the file
        std::istringstream in(text);
        tinyobj::LoadMtl(map, materials, &in, warn, err);
        files.push_back(path);
        return true;
    }

    std::vector<std::string> files;

private:
    const std::string& objPath_;
    const FileReader& read_;
    const PathPolicy& paths_;
};

glm::vec3 clampedColour(const tinyobj::real_t* c) {
    return glm::clamp(glm::vec3(float(c[0]), float(c[1]), float(c[2])), glm::vec3(0.0f), glm::vec3(1.0f));
}

bool anyPositive(glm::vec3 c) { return c.x > 0.0f || c.y > 0.0f || c.z > 0.0f; }

// Whether an MTL material uses the PBR extension's keys (Pr roughness, Pm metallic, or their maps).
bool usesPbrKeys(const tinyobj::material_t& m) {
    return m.roughness > 0.0f || m.metallic > 0.0f || !m.roughness_texname.empty() || !m.metallic_texname.empty();
}

// An MTL material as Photon's (the table of docs/scenes.md).
Material fromMtl(const tinyobj::material_t& m) {
    glm::vec3 kd = clampedColour(m.diffuse);
    glm::vec3 ks = clampedColour(m.specular);
    glm::vec3 ke(std::max(0.0f, float(m.emission[0])), std::max(0.0f, float(m.emission[1])),
                 std::max(0.0f, float(m.emission[2])));
    if (!std::isfinite(ke.x + ke.y + ke.z) || ke.x > 1e30f || ke.y > 1e30f || ke.z > 1e30f) {
        ke = glm::vec3(0.0f);
    }
    Material out;
    bool transparent = m.illum == 4 || m.illum == 6 || m.illum == 7 || m.illum == 9 || m.dissolve < 0.999f;
    bool mirrored = m.illum == 3 || m.illum == 5;
    if (usesPbrKeys(m)) {
        // The PBR extension of MTL (Pr, Pm; Blender and exporters of glTF-like materials): glTF's model.
        float roughness = std::isfinite(m.roughness) ? std::clamp(float(m.roughness), 0.0f, 1.0f) : 1.0f;
        float metallic = std::isfinite(m.metallic) ? std::clamp(float(m.metallic), 0.0f, 1.0f) : 0.0f;
        out = makePbr(kd, metallic, roughness);
        if (m.ior >= 1.0f && m.ior <= 10.0f) {
            out.ior = float(m.ior);
        }
        if (transparent) {
            // d < 1 is the share that passes; the transparent illumination models alone mean glass.
            out.transmission = m.dissolve < 0.999f ? 1.0f - std::clamp(float(m.dissolve), 0.0f, 1.0f) : 1.0f;
        }
    } else if (transparent) {
        glm::vec3 tf = clampedColour(m.transmittance);
        float ior = m.ior > 1.0f && m.ior < 10.0f ? float(m.ior) : 1.5f;
        out = makeGlass(ior, anyPositive(tf) ? tf : glm::vec3(1.0f));
    } else if (mirrored && anyPositive(ks)) {
        if (anyPositive(kd)) {
            // Base and coat together reflect at most everything.
            float excess = std::max({kd.x + ks.x, kd.y + ks.y, kd.z + ks.z});
            out = makeReflective(excess > 1.0f ? kd / excess : kd, excess > 1.0f ? ks / excess : ks);
        } else {
            out = makeMirror(ks);
        }
    } else if (m.illum == 2 && anyPositive(ks) && m.shininess > 0.0f) {
        float excess = std::max({kd.x + ks.x, kd.y + ks.y, kd.z + ks.z});
        float alpha = std::clamp(std::sqrt(2.0f / (float(m.shininess) + 2.0f)), 0.001f, 1.0f);
        out = makeGlossy(excess > 1.0f ? kd / excess : kd, excess > 1.0f ? ks / excess : ks, alpha);
    } else {
        out = makeDiffuse(kd);
    }
    out.emission = ke;  // any surface may emit; finalize() makes emitting triangles an area light
    return out;
}

}  // namespace

ModelExtras addObjModel(Scene& scene, const std::string& path, const std::string& file, const ModelOptions& options,
                        const FileReader& read) {
    std::string text = withoutBom(file);
    checkObjText(path, text);
    mtllibSeparators(text);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn;
    std::string err;
    std::istringstream in(text);
    MtlReader mtl(path, read, options.paths);
    bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &mtl, true, false);
    if (!ok) {
        throw InputError(path + ": " + (err.empty() ? std::string("not an OBJ file") : err.substr(0, err.find('\n'))));
    }

    // Materials: the scene's override, or each MTL material (and one default grey).
    std::vector<std::uint32_t> sceneMaterial(materials.size());
    std::uint32_t fallback = options.material;
    if (options.material == NONE) {
        for (std::size_t i = 0; i < materials.size(); ++i) {
            Material m = fromMtl(materials[i]);
            std::string folder = folderOf(mtl.files.empty() ? path : mtl.files.front());
            auto image = [&](const std::string& name, TextureEncoding encoding) {
                std::string mapFile = namedFile(folder, name);
                checkNamedFile(path, mapFile, "texture map", options.paths);
                return addImageTexture(scene, read(mapFile, "texture"), WRAP_REPEAT, WRAP_REPEAT, mapFile, encoding);
            };
            if (!materials[i].diffuse_texname.empty() && (m.type == MATERIAL_DIFFUSE || m.type == MATERIAL_GLOSSY ||
                                                          m.type == MATERIAL_REFLECTIVE || m.type == MATERIAL_PBR)) {
                m.albedoTexture = image(materials[i].diffuse_texname, TextureEncoding::Srgb);
                if (!anyPositive(m.albedo)) {
                    m.albedo = glm::vec3(1.0f);  // map_Kd alone: the texture is the colour
                }
            }
            if (m.type == MATERIAL_PBR) {
                // Normal maps: "norm", or "map_Bump" as PBR exporters write them (in older MTL files
                // without PBR keys map_Bump is a height map, which Photon does not read).
                const std::string& normals =
                    materials[i].normal_texname.empty() ? materials[i].bump_texname : materials[i].normal_texname;
                if (!normals.empty()) {
                    m.normalTexture = image(normals, TextureEncoding::Linear);
                    float scale = materials[i].normal_texname.empty() ? materials[i].bump_texopt.bump_multiplier
                                                                      : materials[i].normal_texopt.bump_multiplier;
                    m.normalScale = std::isfinite(scale) && scale != 0.0f ? std::clamp(scale, -100.0f, 100.0f) : 1.0f;
                }
                if (!materials[i].emissive_texname.empty() && !isBlack(m.emission)) {
                    m.emissionTexture = image(materials[i].emissive_texname, TextureEncoding::Srgb);
                }
            }
            sceneMaterial[i] = scene.addMaterial(path + "#" + materials[i].name, m);
        }
        fallback = scene.addMaterial(path + "#default", makeDiffuse(glm::vec3(0.8f)));
    }

    // Vertices: one for each distinct (position, texture coordinate, normal) corner.
    Mesh mesh;
    struct CornerHash {
        std::size_t operator()(const glm::ivec3& c) const {
            return std::size_t((std::uint64_t(std::uint32_t(c.x)) * 0x9E3779B97F4A7C15ull) ^
                               (std::uint64_t(std::uint32_t(c.y)) * 0xC2B2AE3D27D4EB4Full) ^ std::uint64_t(std::uint32_t(c.z)));
        }
    };
    std::unordered_map<glm::ivec3, std::uint32_t, CornerHash> corners;
    bool texcoords = !attrib.texcoords.empty();
    bool normals = !attrib.normals.empty();
    auto vertexOf = [&](const tinyobj::index_t& index) {
        glm::ivec3 key(index.vertex_index, index.texcoord_index, index.normal_index);
        auto [it, inserted] = corners.emplace(key, std::uint32_t(mesh.positions.size()));
        if (inserted) {
            // checkObjText has reported bad indices with their line; this holds wherever
            // tinyobjloader reads a line otherwise than it does.
            if (index.vertex_index < 0 || 3 * std::size_t(index.vertex_index) + 2 >= attrib.vertices.size() ||
                (index.texcoord_index >= 0 && 2 * std::size_t(index.texcoord_index) + 1 >= attrib.texcoords.size()) ||
                (index.normal_index >= 0 && 3 * std::size_t(index.normal_index) + 2 >= attrib.normals.size())) {
                throw InputError(path + ": a face refers to a vertex, texture coordinate or normal that does not exist");
            }
            const tinyobj::real_t* v = &attrib.vertices[3 * std::size_t(index.vertex_index)];
            mesh.positions.emplace_back(float(v[0]), float(v[1]), float(v[2]));
            if (texcoords) {
                glm::vec2 st(0.0f);
                if (index.texcoord_index >= 0) {
                    const tinyobj::real_t* t = &attrib.texcoords[2 * std::size_t(index.texcoord_index)];
                    st = glm::vec2(float(t[0]), 1.0f - float(t[1]));  // OBJ's t runs upwards
                }
                mesh.texcoords.push_back(st);
            }
            if (normals) {
                glm::vec3 n(0.0f);
                if (index.normal_index >= 0) {
                    const tinyobj::real_t* nv = &attrib.normals[3 * std::size_t(index.normal_index)];
                    n = glm::vec3(float(nv[0]), float(nv[1]), float(nv[2]));
                }
                mesh.normals.push_back(n);
            }
        }
        return it->second;
    };
    for (const tinyobj::shape_t& shape : shapes) {
        std::size_t at = 0;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            std::size_t n = shape.mesh.num_face_vertices[f];
            if (n == 3) {
                glm::uvec3 t(vertexOf(shape.mesh.indices[at]), vertexOf(shape.mesh.indices[at + 1]),
                             vertexOf(shape.mesh.indices[at + 2]));
                int m = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
                mesh.triangles.push_back(t);
                mesh.materials.push_back(m >= 0 && std::size_t(m) < sceneMaterial.size() && options.material == NONE
                                             ? sceneMaterial[std::size_t(m)]
                                             : fallback);
            }
            at += n;
        }
    }
    if (mesh.triangles.empty()) {
        throw InputError(path + ": no triangles: the file has no faces");
    }
    scene.addMesh(mesh, options.transform);
    return {};
}

}  // namespace photon
