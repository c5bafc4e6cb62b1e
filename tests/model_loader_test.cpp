// Model loader tests: OBJ + MTL and glTF land in the Scene as docs/scenes.md says (geometry under
// its transforms, the material table, textures decoded to linear, cameras and lights in their
// units), and every kind of bad file is one InputError naming the file, the place and the reason.
#include "core/loaders/model_loader.h"
#include "shared/light_types.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <glm/gtc/matrix_transform.hpp>
#include <meshoptimizer.h>

#include "core/image/image.h"
#include "core/system/error.h"
#include "shared/material.h"
#include "shared/math.h"
#include "test_util.h"

namespace photon {
namespace {

// ---- Fixtures -------------------------------------------------------------------------------------

// Companion files (MTL, images, .bin buffers) held in memory; a missing one fails as on disk.
struct Files {
    std::map<std::string, std::string> files;

    FileReader reader() const {
        return [this](const std::string& path, const char* what) {
            auto it = files.find(path);
            if (it == files.end()) {
                throw InputError(path + ": cannot open the " + std::string(what) + ": No such file or directory");
            }
            return it->second;
        };
    }
};

ModelExtras load(Scene& scene, const std::string& path, const std::string& bytes, const Files& files = {},
                 ModelOptions options = {}) {
    return addModel(scene, path, bytes, options, files.reader());
}

std::string errorOf(const std::string& path, const std::string& bytes, const Files& files = {}) {
    try {
        Scene scene;
        load(scene, path, bytes, files);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(loaded)";
}

// A PNG of 2×1 texels (sRGB 255,128,0 and 0,0,255) as bytes.
std::string twoTexelPng() {
    std::filesystem::path file = std::filesystem::temp_directory_path() / ("photon-texture-" + std::to_string(::getpid()) + ".png");
    const unsigned char rgb[6] = {255, 128, 0, 0, 0, 255};
    writeRgb8Png(file.string(), rgb, 2, 1);
    std::ifstream in(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::filesystem::remove(file);
    return bytes;
}

glm::vec3 texel(const Scene& scene, std::uint32_t texture, std::uint32_t x, std::uint32_t y) {
    const Texture& t = scene.textures[texture];
    glm::uvec2 p = scene.texels[t.offset + y * t.width + x];
    return glm::vec3(float(p.x & 0xffffu), float(p.x >> 16u), float(p.y & 0xffffu)) / 65535.0f;
}

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

std::string base64(const std::string& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t n = std::uint32_t(std::uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) n |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) n |= std::uint32_t(std::uint8_t(bytes[i + 2]));
        out += digits[(n >> 18) & 63];
        out += digits[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? digits[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? digits[n & 63] : '=';
    }
    return out;
}

template <typename T>
void append(std::string& bytes, const std::vector<T>& values) {
    bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// A glTF of one triangle list: positions (accessor 0), 16-bit indices (accessor 1), texture
// coordinates (accessor 2), in one data-URI buffer; `parts` adds or replaces top-level members.
struct Gltf {
    std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::vector<std::uint16_t> indices = {0, 1, 2};
    std::vector<float> texcoords = {0, 0, 1, 0, 0, 1};
    std::map<std::string, std::string> parts = {
        {"scene", "0"},
        {"scenes", R"([{"nodes": [0]}])"},
        {"nodes", R"([{"mesh": 0}])"},
        {"meshes", R"([{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 2}, "indices": 1, "material": 0}]}])"},
        {"materials", R"([{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 0.125, 1], "metallicFactor": 0}}])"},
    };

    // The triangle `count` times, triangle i in mesh i of material i under root node i.
    void trianglePerMaterial(int count) {
        std::string meshes = "[";
        std::string nodes = "[";
        std::string roots = "[";
        for (int i = 0; i < count; ++i) {
            std::string n = std::to_string(i);
            meshes += (i ? "," : "") + std::string(R"({"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": )") + n + "}]}";
            nodes += (i ? "," : "") + std::string(R"({"mesh": )") + n + "}";
            roots += (i ? "," : "") + n;
        }
        parts["meshes"] = meshes + "]";
        parts["nodes"] = nodes + "]";
        parts["scenes"] = R"([{"nodes": )" + roots + "]}]";
    }

    std::string data() const {
        std::string bytes;
        append(bytes, positions);
        append(bytes, indices);
        while (bytes.size() % 4 != 0) bytes += '\0';
        append(bytes, texcoords);
        return bytes;
    }

    std::string text() const {
        std::string data = this->data();
        std::size_t indexOffset = positions.size() * 4;
        std::size_t texOffset = data.size() - texcoords.size() * 4;
        std::size_t vertices = positions.size() / 3;
        std::ostringstream s;
        s << R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": )" << data.size()
          << R"(, "uri": "data:application/octet-stream;base64,)" << base64(data) << R"("}], "bufferViews": [)"
          << R"({"buffer": 0, "byteOffset": 0, "byteLength": )" << indexOffset << "},"
          << R"({"buffer": 0, "byteOffset": )" << indexOffset << R"(, "byteLength": )" << indices.size() * 2 << "},"
          << R"({"buffer": 0, "byteOffset": )" << texOffset << R"(, "byteLength": )" << texcoords.size() * 4 << "}],"
          << R"("accessors": [{"bufferView": 0, "componentType": 5126, "count": )" << vertices << R"(, "type": "VEC3"},)"
          << R"({"bufferView": 1, "componentType": 5123, "count": )" << indices.size() << R"(, "type": "SCALAR"},)"
          << R"({"bufferView": 2, "componentType": 5126, "count": )" << texcoords.size() / 2 << R"(, "type": "VEC2"}])";
        for (const auto& [key, value] : parts) {
            s << ", \"" << key << "\": " << value;
        }
        s << "}";
        return s.str();
    }
};

void expectNear(glm::vec3 a, glm::vec3 b, float tolerance = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

const char* const kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

// ---- OBJ ------------------------------------------------------------------------------------------

// Texture 0 is a real texture: a material without one must say NONE, or every triangle with
// texture coordinates samples another material's image (or, with no textures at all, memory
// that is not there).
TEST(ObjLoader, TextureCoordinatesWithoutAnImageSampleNothing) {
    Scene scene;
    load(scene, "uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n");
    ASSERT_FALSE(scene.materials.empty());
    for (const Material& m : scene.materials) {
        EXPECT_EQ(m.albedoTexture, NONE);
    }
    for (Material m : {makeDiffuse(glm::vec3(1.0f)), makeMirror(glm::vec3(1.0f)), makeGlass(1.5f, glm::vec3(1.0f)),
                       makeGlossy(glm::vec3(0.5f), glm::vec3(0.5f), 0.1f), makeReflective(glm::vec3(0.5f), glm::vec3(0.5f)),
                       makeEmitter(glm::vec3(1.0f))}) {
        EXPECT_EQ(m.albedoTexture, NONE);
    }
}

TEST(ObjLoader, PolygonsAreTriangulatedUnderTheTransform) {
    Scene scene;
    ModelOptions options;
    options.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5)) * glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));
    load(scene, "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", {}, options);
    ASSERT_EQ(scene.triangles.size(), 2u);
    EXPECT_EQ(scene.objects.size(), 1u);
    float area = 0.0f;
    for (const Triangle& t : scene.triangles) {
        for (glm::vec3 v : {t.v0, t.v1, t.v2}) {
            EXPECT_FLOAT_EQ(v.z, 5.0f);
            EXPECT_TRUE((v.x == 0.0f || v.x == 2.0f) && (v.y == 0.0f || v.y == 2.0f));
        }
        glm::vec3 n = glm::cross(t.v1 - t.v0, t.v2 - t.v0);
        EXPECT_GT(n.z, 0.0f) << "the triangles keep the polygon's winding";
        area += 0.5f * glm::length(n);
    }
    EXPECT_FLOAT_EQ(area, 4.0f);
    EXPECT_EQ(scene.materialNames[scene.triangles[0].material], "quad.obj#default");
}

TEST(ObjLoader, NegativeIndicesAndSmoothNormalsAndTextureCoordinates) {
    Scene scene;
    load(scene, "t.obj",
         "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0.6 0 0.8\n"
         "f -3/-3/-3 -2/-2/-2 -1/-1/-1\n");
    ASSERT_EQ(scene.triangles.size(), 1u);
    ASSERT_NE(scene.triangles[0].attributes, NONE);
    const TriangleAttributes& a = scene.triangleAttributes[scene.triangles[0].attributes];
    // OBJ's t runs up, Photon's (glTF's) down.
    EXPECT_FLOAT_EQ(a.s1, 1.0f);
    EXPECT_FLOAT_EQ(a.t1, 1.0f);
    EXPECT_FLOAT_EQ(a.t2, 0.0f);
    glm::vec3 n2 = octDecode(a.normal2);
    EXPECT_NEAR(n2.x, 0.6f, 1e-3f);
    EXPECT_NEAR(n2.z, 0.8f, 1e-3f);
}

TEST(ObjLoader, MtlMaterialsMapAsDocumented) {
    Files files;
    files.files["m/scene.mtl"] =
        "newmtl matte\nKd 0.5 0.25 0.125\nillum 1\n"
        "newmtl plastic\nKd 0.5 0.5 0.5\nKs 0.25 0.25 0.25\nNs 100\nillum 2\n"
        "newmtl chrome\nKd 0 0 0\nKs 0.9 0.9 0.9\nillum 3\n"
        "newmtl glass\nKd 0 0 0\nNi 1.33\nTf 0.9 1 0.9\nillum 7\n"
        "newmtl lamp\nKd 0 0 0\nKe 4 4 2\n";
    std::string obj = "mtllib scene.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (const char* m : {"matte", "plastic", "chrome", "glass", "lamp"}) {
        obj += std::string("usemtl ") + m + "\nf 1 2 3\n";
    }
    Scene scene;
    load(scene, "m/scene.obj", obj, files);
    ASSERT_EQ(scene.triangles.size(), 5u);
    auto material = [&](int i) { return scene.materials[scene.triangles[std::size_t(i)].material]; };
    EXPECT_EQ(material(0).type, MATERIAL_DIFFUSE);
    expectNear(material(0).albedo, glm::vec3(0.5f, 0.25f, 0.125f));
    EXPECT_EQ(material(1).type, MATERIAL_GLOSSY);
    expectNear(material(1).specular, glm::vec3(0.25f));
    EXPECT_NEAR(material(1).roughness, std::sqrt(2.0f / 102.0f), 1e-5f);  // Blinn–Phong Ns as GGX α
    EXPECT_EQ(material(2).type, MATERIAL_MIRROR);
    expectNear(material(2).specular, glm::vec3(0.9f));
    EXPECT_EQ(material(3).type, MATERIAL_GLASS);
    EXPECT_FLOAT_EQ(material(3).ior, 1.33f);
    expectNear(material(3).specular, glm::vec3(0.9f, 1.0f, 0.9f));
    expectNear(material(4).emission, glm::vec3(4, 4, 2));
    EXPECT_EQ(scene.materialNames[scene.triangles[3].material], "m/scene.obj#glass");
    scene.finalize();
    bool emissiveLight = false;
    for (const Light& l : scene.lights) {
        emissiveLight |= l.type == LIGHT_TRIANGLES && l.emitterCount == 1;
    }
    EXPECT_TRUE(emissiveLight) << "Ke makes the triangle an area light";
}

TEST(ObjLoader, DiffuseMapIsDecodedFromSrgbToLinear) {
    Files files;
    files.files["a.mtl"] = "newmtl tex\nKd 1 1 1\nmap_Kd tex.png\n";
    files.files["tex.png"] = twoTexelPng();
    Scene scene;
    load(scene, "a.obj", "mtllib a.mtl\nusemtl tex\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", files);
    const Material& m = scene.materials[scene.triangles[0].material];
    ASSERT_NE(m.albedoTexture, NONE);
    const Texture& t = scene.textures[m.albedoTexture];
    EXPECT_EQ(t.width, 2u);
    EXPECT_EQ(t.height, 1u);
    EXPECT_EQ(t.wrap, WRAP_REPEAT | (WRAP_REPEAT << 4u));
    expectNear(texel(scene, m.albedoTexture, 0, 0), glm::vec3(1.0f, srgbToLinear(128.0f / 255.0f), 0.0f), 1e-4f);
    expectNear(texel(scene, m.albedoTexture, 1, 0), glm::vec3(0.0f, 0.0f, 1.0f), 1e-4f);
}

// A 16-bit PPM is refused by name: stb_image's conversion of it to four channels overflows its
// buffer (the render fuzzer found it through an MTL's map_Kd).
TEST(ObjLoader, SixteenBitImagesOtherThanPngAreRefused) {
    Files files;
    files.files["a.mtl"] = "newmtl tex\nKd 1 1 1\nmap_Kd tex.ppm\n";
    files.files["tex.ppm"] = std::string("P6\n2 2\n65535\n") + std::string(2 * 2 * 3 * 2, '\x7f');
    Scene scene;
    try {
        load(scene, "a.obj", "mtllib a.mtl\nusemtl tex\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", files);
        FAIL() << "a 16-bit PPM was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("tex.ppm: a 16-bit image that is not a PNG"), std::string::npos) << e.what();
    }
}

TEST(ObjLoader, SceneMaterialOverridesTheFiles) {
    Files files;
    files.files["a.mtl"] = "newmtl red\nKd 1 0 0\n";
    Scene scene;
    ModelOptions options;
    options.material = scene.addMaterial("glass", makeGlass(1.5f, glm::vec3(1.0f)));
    load(scene, "a.obj", "mtllib a.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", files, options);
    EXPECT_EQ(scene.triangles[0].material, options.material);
    EXPECT_EQ(scene.materials.size(), 1u) << "no materials are made for a file whose materials are overridden";
}

TEST(ObjLoader, ZeroAreaTrianglesAreDroppedAndCounted) {
    Scene scene;
    load(scene, "z.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 1 1 3\n");
    EXPECT_EQ(scene.triangles.size(), 1u);
    EXPECT_EQ(scene.droppedTriangles, 2u);
}

// A model with nothing to render is refused, not rendered black (or, as a scene's only mesh, left
// to an automatic radius of 0 with a message about --radius).
TEST(ModelLoader, NoTrianglesToRenderIsAnError) {
    EXPECT_EQ(errorOf("z.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n"),
              "z.obj: no triangles: all 2 have no area or are not finite");
    Gltf points;
    points.parts["meshes"] = R"([{"primitives": [{"attributes": {"POSITION": 0}, "mode": 0}]}])";
    EXPECT_EQ(errorOf("p.gltf", points.text()), "p.gltf: no triangles: its primitives are points or lines only");
    Gltf noNodes;
    noNodes.parts["scenes"] = R"([{"nodes": []}])";
    EXPECT_EQ(errorOf("n.gltf", noNodes.text()), "n.gltf: no triangles: its scene has no nodes");
    // A second model may add nothing of its own either: each is judged by what it added.
    Scene scene;
    load(scene, "a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_THROW(load(scene, "p.gltf", points.text()), InputError);
}

TEST(ObjLoader, BadFilesNameTheLineAndTheReason) {
    EXPECT_EQ(errorOf("b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
              "b.obj: line 4: vertex index '4' out of range (3 defined before this line)");
    EXPECT_EQ(errorOf("b.obj", "v 0 0 0\nv nan 0 0\n"), "b.obj: line 2: 'nan' is not a finite number");
    EXPECT_EQ(errorOf("b.obj", "v 0 0 0\nv 1e39 0 0\n"), "b.obj: line 2: '1e39' is not a finite number");
    EXPECT_EQ(errorOf("b.obj", "v 0 0\n"), "b.obj: line 1: v needs 3 numbers");
    EXPECT_EQ(errorOf("b.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"), "b.obj: line 3: a face needs 3 corners or more");
    EXPECT_EQ(errorOf("b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n"),
              "b.obj: line 4: texture coordinate index '1' out of range (0 defined before this line)");
    EXPECT_EQ(errorOf("b.obj", "v 0 0 0\n"), "b.obj: no triangles: the file has no faces");
    EXPECT_EQ(errorOf("b.obj", "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
              "gone.mtl: cannot open the MTL file: No such file or directory");
    Files files;
    files.files["t.mtl"] = "newmtl t\nmap_Kd gone.png\n";
    EXPECT_EQ(errorOf("b.obj", "mtllib t.mtl\nusemtl t\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", files),
              "gone.png: cannot open the texture: No such file or directory");
    files.files["bad.png"] = "not an image";
    files.files["t.mtl"] = "newmtl t\nmap_Kd bad.png\n";
    EXPECT_NE(errorOf("b.obj", "mtllib t.mtl\nusemtl t\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", files).find("bad.png: "),
              std::string::npos);
}

// ---- glTF -----------------------------------------------------------------------------------------

TEST(GltfLoader, NodeHierarchyTransformsCompose) {
    Gltf g;
    // Parent: translate (0, 0, 3) and rotate 90° about y; child: scale 2.
    g.parts["nodes"] = R"([{"translation": [0, 0, 3], "rotation": [0, 0.7071067811865476, 0, 0.7071067811865476], "children": [1]},
                          {"scale": [2, 2, 2], "mesh": 0}])";
    Scene scene;
    load(scene, "h.gltf", g.text());
    ASSERT_EQ(scene.triangles.size(), 1u);
    expectNear(scene.triangles[0].v0, glm::vec3(0, 0, 3));
    expectNear(scene.triangles[0].v1, glm::vec3(0, 0, 1));  // x → -z under the rotation
    expectNear(scene.triangles[0].v2, glm::vec3(0, 2, 3));
}

TEST(GltfLoader, MatrixNodesAndMeshesUsedTwice) {
    Gltf g;
    g.parts["scenes"] = R"([{"nodes": [0, 1]}])";
    g.parts["nodes"] = R"([{"mesh": 0}, {"mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 5,0,0,1]}])";
    Scene scene;
    load(scene, "m.gltf", g.text());
    ASSERT_EQ(scene.triangles.size(), 2u);
    expectNear(scene.triangles[1].v0, glm::vec3(5, 0, 0));  // column-major: the translation is last
    EXPECT_EQ(scene.triangles[0].material, scene.triangles[1].material) << "one glTF material, one Photon material";
}

TEST(GltfLoader, MaterialsMapAsDocumented) {
    Gltf g;
    g.parts["extensionsUsed"] = R"(["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength"])";
    g.parts["materials"] = R"([
        {"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 0.125, 1], "metallicFactor": 0, "roughnessFactor": 1}},
        {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 0.7, 1], "metallicFactor": 1, "roughnessFactor": 0}},
        {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 0.7, 1], "metallicFactor": 1, "roughnessFactor": 0.5}},
        {"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 1.7}}},
        {"emissiveFactor": [1, 0.5, 0.25], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}},
        {"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0, "roughnessFactor": 0.3}}])";
    g.trianglePerMaterial(6);
    Scene scene;
    load(scene, "mat.gltf", g.text());
    ASSERT_EQ(scene.triangles.size(), 6u);
    auto material = [&](int i) { return scene.materials[scene.triangles[std::size_t(i)].material]; };
    // Every glTF material is the metallic-roughness model with its factors as they are: no thresholds.
    for (int i = 0; i < 6; ++i) {
        EXPECT_EQ(material(i).type, MATERIAL_PBR);
        EXPECT_EQ(material(i).albedoTexture, NONE);
    }
    expectNear(material(0).albedo, glm::vec3(0.5f, 0.25f, 0.125f));
    EXPECT_FLOAT_EQ(material(0).metallic, 0.0f);
    EXPECT_FLOAT_EQ(material(0).roughness, 1.0f);
    expectNear(material(1).albedo, glm::vec3(0.9f, 0.8f, 0.7f));
    EXPECT_FLOAT_EQ(material(1).metallic, 1.0f);
    EXPECT_FLOAT_EQ(material(1).roughness, 0.0f);
    EXPECT_NEAR(material(2).roughness, 0.25f, 1e-6f);  // α = roughness²
    EXPECT_FLOAT_EQ(material(3).transmission, 1.0f);
    EXPECT_FLOAT_EQ(material(3).ior, 1.7f);
    EXPECT_NE(material(3).flags & MATERIAL_FLAG_THIN_WALLED, 0u) << "no KHR_materials_volume: a thin sheet";
    EXPECT_FLOAT_EQ(material(0).ior, 1.5f);
    expectNear(material(4).emission, glm::vec3(4, 2, 1));
    EXPECT_NEAR(material(5).roughness, 0.09f, 1e-6f);
    // What the flags make of them: a rough dielectric stores photons, a smooth metal and a
    // transmissive glass are traced like mirrors and glass (and are caustic casters).
    EXPECT_TRUE(surfaceIs(material(0), SURFACE_STORES_PHOTONS));
    EXPECT_FALSE(surfaceIs(material(0), SURFACE_SPECULAR_COAT));
    EXPECT_TRUE(surfaceIs(material(1), SURFACE_CAUSTIC_CASTER));
    EXPECT_TRUE(surfaceIs(material(2), SURFACE_STORES_PHOTONS));
    EXPECT_TRUE(surfaceIs(material(3), SURFACE_CAUSTIC_CASTER));
}

TEST(GltfLoader, AlphaModesVolumeAndTextureTransform) {
    Gltf g;
    g.parts["extensionsUsed"] = R"(["KHR_materials_volume", "KHR_materials_transmission", "KHR_texture_transform"])";
    g.parts["materials"] = R"([
        {"alphaMode": "MASK", "alphaCutoff": 0.25, "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.5]}},
        {"alphaMode": "BLEND"},
        {"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                        "KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 2,
                                                 "attenuationColor": [0.5, 1, 0.25]}}}])";
    g.trianglePerMaterial(3);
    Scene scene;
    load(scene, "alpha.gltf", g.text());
    scene.finalize();
    auto material = [&](int i) { return scene.materials[scene.triangles[std::size_t(i)].material]; };
    EXPECT_EQ(material(0).flags & MATERIAL_FLAG_ALPHA_MASK, MATERIAL_FLAG_ALPHA_MASK);
    EXPECT_FLOAT_EQ(material(0).alphaCutoff, 0.25f);
    EXPECT_FLOAT_EQ(material(0).alpha, 0.5f);
    EXPECT_EQ(material(1).flags & MATERIAL_FLAG_ALPHA_BLEND, MATERIAL_FLAG_ALPHA_BLEND);
    // Single-sided (doubleSided defaults to false) and opaque: culled from behind; the glass is not.
    EXPECT_EQ(scene.triangles[0].flags, TRIANGLE_ALPHA_TESTED | TRIANGLE_BACK_CULLED);
    EXPECT_EQ(scene.triangles[1].flags, TRIANGLE_ALPHA_TESTED | TRIANGLE_BACK_CULLED);
    EXPECT_EQ(scene.triangles[2].flags, 0u);
    EXPECT_EQ(material(2).flags & MATERIAL_FLAG_THIN_WALLED, 0u) << "a volume refracts";
    // σ = −ln(colour) / distance.
    expectNear(material(2).attenuation, glm::vec3(std::log(2.0f) / 2.0f, 0.0f, std::log(4.0f) / 2.0f), 1e-5f);
}

TEST(GltfLoader, BaseColourTextureWithItsSampler) {
    Gltf g;
    std::string png = twoTexelPng();
    g.parts["images"] = R"([{"uri": "data:image/png;base64,)" + base64(png) + R"("}])";
    g.parts["samplers"] = R"([{"wrapS": 33071, "wrapT": 33648}])";
    g.parts["textures"] = R"([{"source": 0, "sampler": 0}])";
    g.parts["materials"] = R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}])";
    Scene scene;
    load(scene, "tex.gltf", g.text());
    const Material& m = scene.materials[scene.triangles[0].material];
    ASSERT_NE(m.albedoTexture, NONE);
    EXPECT_EQ(scene.textures[m.albedoTexture].wrap, WRAP_CLAMP | (WRAP_MIRRORED_REPEAT << 4u));
    expectNear(texel(scene, m.albedoTexture, 0, 0), glm::vec3(1.0f, srgbToLinear(128.0f / 255.0f), 0.0f), 1e-4f);
    const TriangleAttributes& a = scene.triangleAttributes[scene.triangles[0].attributes];
    EXPECT_FLOAT_EQ(a.s1, 1.0f);
    EXPECT_FLOAT_EQ(a.t2, 1.0f);
}

TEST(GltfLoader, ExternalBufferAndImageAreReadBesideTheFile) {
    Gltf g;
    std::string text = g.text();
    // Move the buffer out of the data URI into dir/mesh.bin.
    std::size_t uri = text.find("data:application/octet-stream;base64,");
    std::size_t end = text.find('"', uri);
    text.replace(uri, end - uri, "mesh.bin");
    Files files;
    files.files["dir/mesh.bin"] = g.data();
    Scene scene;
    load(scene, "dir/ext.gltf", text, files);
    EXPECT_EQ(scene.triangles.size(), 1u);
    EXPECT_NE(errorOf("dir/ext.gltf", text).find("mesh.bin"), std::string::npos);
}

TEST(GltfLoader, CameraAndPunctualLightsInPhotonUnits) {
    Gltf g;
    g.parts["extensionsUsed"] = R"(["KHR_lights_punctual"])";
    g.parts["extensions"] = R"({"KHR_lights_punctual": {"lights": [
        {"type": "point", "intensity": 683, "color": [1, 0.5, 1]},
        {"type": "directional", "intensity": 6830},
        {"type": "spot", "intensity": 683, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}}]}})";
    g.parts["cameras"] = R"([{"type": "perspective", "perspective": {"yfov": 0.7853981633974483, "znear": 0.1}}])";
    g.parts["scenes"] = R"([{"nodes": [0, 1, 2, 3, 4]}])";
    g.parts["nodes"] = R"([{"mesh": 0},
        {"camera": 0, "translation": [0, 1, 5]},
        {"translation": [0, 4, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"rotation": [-0.7071067811865476, 0, 0, 0.7071067811865476], "extensions": {"KHR_lights_punctual": {"light": 1}}},
        {"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 2}}}])";
    Scene scene;
    ModelOptions options;
    options.cameraAndLights = true;
    ModelExtras extras = load(scene, "cl.gltf", g.text(), {}, options);
    ASSERT_TRUE(extras.hasCamera);
    expectNear(extras.camera.position, glm::vec3(0, 1, 5));
    expectNear(extras.camera.lookAt, glm::vec3(0, 1, 4));  // glTF cameras look down -z
    EXPECT_NEAR(extras.camera.fovY, 45.0f, 1e-4f);
    EXPECT_EQ(extras.lights, 3u);
    ASSERT_EQ(scene.lights.size(), 3u);
    // 683 cd at 683 lm/W is 1 W/sr: 4π W in all directions.
    EXPECT_EQ(scene.lights[0].type, LIGHT_POINT);
    expectNear(scene.lights[0].position, glm::vec3(0, 4, 0));
    expectNear(scene.lights[0].power, glm::vec3(4.0f * PI, 2.0f * PI, 4.0f * PI), 1e-4f);
    // 6830 lux is 10 W/m², travelling down the node's -z (here straight down).
    EXPECT_EQ(scene.lights[1].type, LIGHT_DIRECTIONAL);
    expectNear(directionalIrradiance(scene.lights[1]), glm::vec3(10.0f), 1e-4f);
    expectNear(scene.lights[1].axis, glm::vec3(0, -1, 0));
    EXPECT_EQ(scene.lights[2].type, LIGHT_SPOT);
    expectNear(scene.lights[2].axis, glm::vec3(0, 0, -1));
    EXPECT_NEAR(scene.lights[2].spotOuter, 1.0f - std::cos(0.5f), 1e-5f);
    // Without cameraAndLights (a mesh object in a scene file) the file brings geometry only.
    Scene geometryOnly;
    extras = load(geometryOnly, "cl.gltf", g.text());
    EXPECT_FALSE(extras.hasCamera);
    EXPECT_TRUE(geometryOnly.lights.empty());
}

TEST(GltfLoader, BadFilesNameTheJsonPointerAndTheReason) {
    {
        Gltf g;
        g.indices = {0, 1, 3};
        EXPECT_EQ(errorOf("b.gltf", g.text()), "b.gltf: /accessors/1: index 3 at element 2 out of range (3 vertices)");
    }
    {
        Gltf g;
        g.positions[4] = std::nanf("");
        EXPECT_EQ(errorOf("b.gltf", g.text()), "b.gltf: /accessors/0: element 1 is not finite");
    }
    {
        Gltf g;
        g.parts["nodes"] = R"([{"mesh": 0, "children": [1]}, {"children": [0]}])";
        EXPECT_EQ(errorOf("b.gltf", g.text()), "b.gltf: /nodes/0: a cycle in the node hierarchy");
    }
    {
        Gltf g;
        g.parts["extensionsRequired"] = R"(["KHR_mesh_quantization", "EXT_texture_webp"])";
        g.parts["extensionsUsed"] = R"(["KHR_mesh_quantization", "EXT_texture_webp"])";
        EXPECT_EQ(errorOf("b.gltf", g.text()),
                  "b.gltf: /extensionsRequired/1: the required extension 'EXT_texture_webp' is not supported");
    }
    {
        Gltf g;
        g.parts["meshes"] = R"([{"primitives": [{"attributes": {"POSITION": 7}}]}])";
        EXPECT_EQ(errorOf("b.gltf", g.text()), "b.gltf: /meshes/0/primitives/0: accessor 7 does not exist");
    }
    for (const char* ior : {"0", "0.5"}) {
        Gltf g;
        g.parts["extensionsUsed"] = R"(["KHR_materials_ior"])";
        g.parts["materials"] = std::string(R"([{"extensions": {"KHR_materials_ior": {"ior": )") + ior + "}}}]";
        g.parts["meshes"] = R"([{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}])";
        std::string reason = ior[1] ? "must be from 1 to 10" : "0 (a reflectance of 1) is not supported: use 1 to 10";
        EXPECT_EQ(errorOf("b.gltf", g.text()), "b.gltf: /materials/0/extensions/KHR_materials_ior/ior: " + reason);
    }
    {
        Gltf g;
        g.parts["meshes"] = R"([{"primitives": [{"attributes": {"POSITION": 0}, "material": 3}]}])";
        EXPECT_EQ(errorOf("b.gltf", g.text()), "b.gltf: /meshes/0/primitives/0/material: material 3 does not exist");
    }
    {
        Gltf g;
        g.parts["materials"] = R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}])";
        g.parts["textures"] = R"([{"source": 0}])";
        g.parts["images"] = R"([{"uri": "gone.png"}])";
        std::string e = errorOf("d/b.gltf", g.text());
        EXPECT_NE(e.find("gone.png"), std::string::npos) << e;
    }
    {
        Gltf g;
        std::string text = g.text();
        std::size_t length = text.find("\"byteLength\": ") + 14;
        text.replace(length, text.find(',', length) - length, "4");  // the buffer shorter than its data
        EXPECT_EQ(errorOf("b.gltf", text).rfind("b.gltf: ", 0), 0u) << errorOf("b.gltf", text);
    }
    {
        // tinygltf passes an image's buffer view on without checking it against the buffer (found
        // by the fuzzer: a heap overflow in keepImage).
        Gltf g;
        g.parts["images"] = R"([{"bufferView": 3, "mimeType": "image/png"}])";
        std::string text = g.text();
        std::size_t views = text.find(R"("bufferViews": [)") + 16;
        text.insert(text.find("}]", views) + 1, R"(, {"buffer": 0, "byteOffset": 8, "byteLength": 100000})");
        EXPECT_EQ(errorOf("b.gltf", text), "b.gltf: /images/0: buffer view 3 extends beyond its buffer of " +
                                               std::to_string(g.data().size()) + " bytes");
    }
    {
        // A binary chunk whose length counts its own header: tinygltf read 8 bytes past the file
        // (found by the fuzzer).
        Gltf g;
        std::string text = g.text();
        std::size_t uri = text.find(R"(, "uri": ")");
        text.erase(uri, text.find('"', uri + 10) + 1 - uri);  // the buffer is the binary chunk
        while (text.size() % 4 != 0) text += ' ';
        std::string bin = g.data();
        std::string glb = "glTF";
        auto word = [&](std::size_t w) {
            std::uint32_t x = std::uint32_t(w);
            glb.append(reinterpret_cast<const char*>(&x), 4);
        };
        word(2);
        word(12 + 8 + text.size() + 8 + bin.size());
        word(text.size());
        glb += "JSON" + text;
        word(bin.size() + 8);
        glb += "BIN";
        glb += '\0';
        glb += bin;
        EXPECT_EQ(errorOf("b.glb", glb), "b.glb: the binary chunk of " + std::to_string(bin.size() + 8) +
                                             " bytes extends beyond the file");
        std::uint32_t honest = std::uint32_t(bin.size());
        std::memcpy(&glb[20 + text.size()], &honest, 4);  // the honest length loads
        Scene scene;
        load(scene, "b.glb", glb);
        EXPECT_EQ(scene.triangles.size(), 1u);
    }
    EXPECT_EQ(errorOf("b.glb", "glTF\x02\0\0\0 truncated").rfind("b.glb: ", 0), 0u);
    EXPECT_EQ(errorOf("b.gltf", "{not json").rfind("b.gltf: ", 0), 0u);
}

// ---- glTF built view by view ------------------------------------------------------------------------

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125, kFloat = 5126;

// A glTF of one primitive whose buffer views and accessors are added one by one: view() appends
// bytes to buffer 0 (4-byte aligned) as a buffer view, accessor() describes one; `buffers` and
// `parts` add more buffers and top-level members.
struct GltfBuilder {
    std::string data;
    std::vector<std::string> views;
    std::vector<std::string> accessors;
    std::vector<std::string> buffers;  // after buffer 0
    std::map<std::string, std::string> parts;

    int view(const std::string& bytes, const std::string& extra = "") {
        while (data.size() % 4 != 0) data += '\0';
        views.push_back(R"({"buffer": 0, "byteOffset": )" + std::to_string(data.size()) + R"(, "byteLength": )" +
                        std::to_string(bytes.size()) + extra + "}");
        data += bytes;
        return int(views.size()) - 1;
    }

    int accessor(int view, int componentType, const char* type, std::size_t count, bool normalized = false) {
        accessors.push_back((view >= 0 ? R"({"bufferView": )" + std::to_string(view) + ", " : std::string("{")) +
                            R"("componentType": )" + std::to_string(componentType) + R"(, "type": ")" + type +
                            R"(", "count": )" + std::to_string(count) + (normalized ? R"(, "normalized": true})" : "}"));
        return int(accessors.size()) - 1;
    }

    // Values as bytes of one component type each, elements `stride` bytes apart (0: packed).
    template <typename T>
    int attribute(const std::vector<T>& values, int componentType, const char* type, int components, bool normalized,
                  std::size_t stride = 0) {
        std::size_t element = sizeof(T) * std::size_t(components);
        stride = stride ? stride : element;
        std::string bytes;
        for (std::size_t i = 0; i < values.size() / std::size_t(components); ++i) {
            bytes.append(reinterpret_cast<const char*>(&values[i * std::size_t(components)]), element);
            bytes.append(stride - element, '\0');
        }
        int v = view(bytes, stride != element ? R"(, "byteStride": )" + std::to_string(stride) : "");
        return accessor(v, componentType, type, values.size() / std::size_t(components), normalized);
    }

    std::string text(const std::string& primitive) const {
        std::ostringstream s;
        s << R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": )" << data.size()
          << R"(, "uri": "data:application/octet-stream;base64,)" << base64(data) << "\"}";
        for (const std::string& b : buffers) s << ", " << b;
        s << R"(], "bufferViews": [)";
        for (std::size_t i = 0; i < views.size(); ++i) s << (i ? ", " : "") << views[i];
        s << R"(], "accessors": [)";
        for (std::size_t i = 0; i < accessors.size(); ++i) s << (i ? ", " : "") << accessors[i];
        s << R"(], "meshes": [{"primitives": [)" << primitive << R"(]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0)";
        for (const auto& [key, value] : parts) s << ", \"" << key << "\": " << value;
        s << "}";
        return s.str();
    }
};

std::string bytesOf(const void* data, std::size_t size) { return std::string(static_cast<const char*>(data), size); }

// ---- KHR_mesh_quantization -------------------------------------------------------------------------

// The glTF spec's rules for integer components: normalized unsigned c/(2ⁿ-1), normalized signed
// max(c/(2ⁿ⁻¹-1), -1), others the integer itself; the node transform (here gltfpack's kind of
// dequantization scale) applies on top.
template <typename T>
void expectQuantizedPositions(int componentType, bool normalized) {
    SCOPED_TRACE(std::to_string(componentType) + (normalized ? " normalized" : ""));
    double max = double(std::numeric_limits<T>::max());
    T lo = std::numeric_limits<T>::min();
    T hi = std::numeric_limits<T>::max();
    std::vector<T> raw = {lo, 0, 0, hi, 0, 0, 0, hi, T(7)};
    GltfBuilder g;
    // Four-byte aligned elements, as the spec asks of vertex attributes (a VEC3 of bytes is 3).
    std::size_t stride = (3 * sizeof(T) + 3) / 4 * 4;
    int position = g.attribute(raw, componentType, "VEC3", 3, normalized, stride);
    g.parts["nodes"] = R"([{"mesh": 0, "scale": [2, 2, 2]}])";
    g.parts["extensionsUsed"] = R"(["KHR_mesh_quantization"])";
    g.parts["extensionsRequired"] = R"(["KHR_mesh_quantization"])";
    Scene scene;
    load(scene, "q.gltf", g.text(R"({"attributes": {"POSITION": )" + std::to_string(position) + "}}"));
    ASSERT_EQ(scene.triangles.size(), 1u);
    auto decode = [&](T c) {
        double x = double(c);
        return float(2.0 * (normalized ? std::max(x / max, -1.0) : x));
    };
    expectNear(scene.triangles[0].v0, glm::vec3(decode(lo), 0, 0));
    expectNear(scene.triangles[0].v1, glm::vec3(decode(hi), 0, 0));
    expectNear(scene.triangles[0].v2, glm::vec3(0, decode(hi), decode(T(7))));
}

TEST(GltfLoader, QuantizedPositionsOfEveryComponentType) {
    for (bool normalized : {false, true}) {
        expectQuantizedPositions<std::int8_t>(kByte, normalized);
        expectQuantizedPositions<std::uint8_t>(kUnsignedByte, normalized);
        expectQuantizedPositions<std::int16_t>(kShort, normalized);
        expectQuantizedPositions<std::uint16_t>(kUnsignedShort, normalized);
    }
    // -128 and -127 both mean -1: the most negative value is clamped, not below -1.
    GltfBuilder g;
    int position = g.attribute(std::vector<std::int8_t>{-128, 0, 0, -127, 1, 0, 0, 0, 1}, kByte, "VEC3", 3, true, 4);
    Scene scene;
    load(scene, "q.gltf", g.text(R"({"attributes": {"POSITION": )" + std::to_string(position) + "}}"));
    ASSERT_EQ(scene.triangles.size(), 1u);
    EXPECT_FLOAT_EQ(scene.triangles[0].v0.x, -1.0f);
    EXPECT_FLOAT_EQ(scene.triangles[0].v1.x, -1.0f);
}

TEST(GltfLoader, QuantizedNormalsTangentsAndTextureCoordinates) {
    GltfBuilder g;
    int position = g.attribute(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}, kFloat, "VEC3", 3, false);
    int normal = g.attribute(std::vector<std::int8_t>{0, 0, 127, 0, 0, 127, 0, 127, 0}, kByte, "VEC3", 3, true, 4);
    int tangent = g.attribute(std::vector<std::int16_t>{32767, 0, 0, -32767, 32767, 0, 0, 32767, 0, 0, 32767, 0},
                              kShort, "VEC4", 4, true);
    int texcoord = g.attribute(std::vector<std::uint16_t>{0, 0, 3, 0, 0, 65535}, kUnsignedShort, "VEC2", 2, false);
    auto primitive = [&](int n, int t, int uv) {
        return R"({"attributes": {"POSITION": )" + std::to_string(position) + R"(, "NORMAL": )" + std::to_string(n) +
               R"(, "TANGENT": )" + std::to_string(t) + R"(, "TEXCOORD_0": )" + std::to_string(uv) + "}}";
    };
    Scene scene;
    load(scene, "q.gltf", g.text(primitive(normal, tangent, texcoord)));
    ASSERT_EQ(scene.triangles.size(), 1u);
    const TriangleAttributes& a = scene.triangleAttributes[scene.triangles[0].attributes];
    expectNear(octDecode(a.normal0), glm::vec3(0, 0, 1), 1e-3f);
    expectNear(octDecode(a.normal2), glm::vec3(0, 1, 0), 1e-3f);
    EXPECT_FLOAT_EQ(a.s1, 3.0f);  // not normalized: the integer itself
    EXPECT_FLOAT_EQ(a.t2, 65535.0f);

    // Unit vectors may only be signed and normalized (KHR_mesh_quantization's table).
    int unsignedNormal = g.attribute(std::vector<std::uint8_t>{0, 0, 255, 0, 0, 255, 0, 0, 255}, kUnsignedByte, "VEC3", 3,
                                     true, 4);
    EXPECT_EQ(errorOf("q.gltf", g.text(primitive(unsignedNormal, tangent, texcoord))),
              "q.gltf: /accessors/" + std::to_string(unsignedNormal) + ": NORMAL must be floats, or normalized signed bytes or shorts");
    int intPositions = g.attribute(std::vector<std::uint32_t>{0, 0, 0, 1, 0, 0, 0, 1, 0}, kUnsignedInt, "VEC3", 3, false);
    EXPECT_EQ(errorOf("q.gltf", g.text(R"({"attributes": {"POSITION": )" + std::to_string(intPositions) + "}}")),
              "q.gltf: /accessors/" + std::to_string(intPositions) + ": POSITION must be floats, bytes or shorts");
    // Tangents are read: four components, one per vertex.
    int shortTangent = g.attribute(std::vector<float>{1, 0, 0, 1, 0, 0, 1, 0, 0}, kFloat, "VEC3", 3, false);
    EXPECT_EQ(errorOf("q.gltf", g.text(primitive(normal, shortTangent, texcoord))),
              "q.gltf: /accessors/" + std::to_string(shortTangent) + ": expected 4 components, got 3");
    int twoTangents = g.attribute(std::vector<float>{1, 0, 0, 1, 1, 0, 0, 1}, kFloat, "VEC4", 4, false);
    EXPECT_EQ(errorOf("q.gltf", g.text(primitive(normal, twoTangents, texcoord))),
              "q.gltf: /meshes/0/primitives/0: NORMAL, TANGENT or TEXCOORD_0 has another count than POSITION");
}

// ---- EXT_meshopt_compression -----------------------------------------------------------------------

// A triangle list compressed as gltfpack writes it: the compressed bytes in buffer 0, the views in
// buffer 1, a fallback with a length and no data (which must never be needed).
struct MeshoptGltf {
    std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    std::vector<std::uint16_t> indices = {0, 1, 2, 2, 1, 3};
    GltfBuilder g;
    std::size_t fallbackLength = 0;

    // A view of `decoded` bytes in the fallback, compressed as `ext` (without its buffer and place).
    int compressed(const std::string& bytes, std::size_t decoded, const std::string& ext, std::size_t stride = 0) {
        while (g.data.size() % 4 != 0) g.data += '\0';
        std::size_t at = g.data.size();
        g.data += bytes;
        g.views.push_back(R"({"buffer": 1, "byteOffset": )" + std::to_string(fallbackLength) + R"(, "byteLength": )" +
                          std::to_string(decoded) + (stride ? R"(, "byteStride": )" + std::to_string(stride) : "") +
                          R"(, "extensions": {"EXT_meshopt_compression": {"buffer": 0, "byteOffset": )" + std::to_string(at) +
                          R"(, "byteLength": )" + std::to_string(bytes.size()) + ", " + ext + "}}}");
        fallbackLength += (decoded + 3) / 4 * 4;
        return int(g.views.size()) - 1;
    }

    std::string text() {
        std::size_t count = positions.size() / 3;
        std::string vertexBytes(meshopt_encodeVertexBufferBound(count, 12), '\0');
        vertexBytes.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(&vertexBytes[0]), vertexBytes.size(),
                                                      positions.data(), count, 12));
        std::string indexBytes(meshopt_encodeIndexBufferBound(indices.size(), count), '\0');
        indexBytes.resize(meshopt_encodeIndexBuffer(reinterpret_cast<unsigned char*>(&indexBytes[0]), indexBytes.size(),
                                                    indices.data(), indices.size()));
        int p = compressed(vertexBytes, count * 12,
                           R"("byteStride": 12, "mode": "ATTRIBUTES", "count": )" + std::to_string(count), 12);
        int i = compressed(indexBytes, indices.size() * 2,
                           R"("byteStride": 2, "mode": "TRIANGLES", "count": )" + std::to_string(indices.size()));
        int position = g.accessor(p, kFloat, "VEC3", count);
        int index = g.accessor(i, kUnsignedShort, "SCALAR", indices.size());
        return finish(R"({"attributes": {"POSITION": )" + std::to_string(position) + R"(}, "indices": )" + std::to_string(index) + "}");
    }

    std::string finish(const std::string& primitive) {
        g.buffers = {R"({"byteLength": )" + std::to_string(fallbackLength) +
                     R"(, "extensions": {"EXT_meshopt_compression": {"fallback": true}}})"};
        g.parts["extensionsUsed"] = R"(["EXT_meshopt_compression"])";
        g.parts["extensionsRequired"] = R"(["EXT_meshopt_compression"])";
        return g.text(primitive);
    }
};

TEST(GltfLoader, MeshoptCompressedViewsDecodeWithoutTheFallback) {
    MeshoptGltf m;
    Scene scene;
    load(scene, "c.gltf", m.text());
    ASSERT_EQ(scene.triangles.size(), 2u);
    expectNear(scene.triangles[0].v1, glm::vec3(1, 0, 0));
    expectNear(scene.triangles[1].v0, glm::vec3(0, 1, 0));
    expectNear(scene.triangles[1].v2, glm::vec3(1, 1, 0));
}

TEST(GltfLoader, MeshoptIndexSequencesAndFilters) {
    // Normals as gltfpack writes them: octahedral, 8 bits, in 4-byte elements.
    MeshoptGltf m;
    std::vector<float> normals = {0, 0, 1, 0, 0.6f, 0, 0.8f, 0, 0, 0.6f, 0.8f, 0, 0, 0, 1, 0};
    std::vector<std::int8_t> oct(16);
    meshopt_encodeFilterOct(oct.data(), 4, 4, 8, normals.data());
    std::string octBytes(meshopt_encodeVertexBufferBound(4, 4), '\0');
    octBytes.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(&octBytes[0]), octBytes.size(), oct.data(), 4, 4));
    int n = m.g.accessor(m.compressed(octBytes, 16, R"("byteStride": 4, "mode": "ATTRIBUTES", "filter": "OCTAHEDRAL", "count": 4)", 4),
                         kByte, "VEC3", 4, true);
    std::string positions(meshopt_encodeVertexBufferBound(4, 12), '\0');
    positions.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(&positions[0]), positions.size(),
                                                m.positions.data(), 4, 12));
    int p = m.g.accessor(m.compressed(positions, 48, R"("byteStride": 12, "mode": "ATTRIBUTES", "count": 4)", 12), kFloat, "VEC3", 4);
    std::vector<std::uint32_t> sequence = {0, 1, 2, 2, 1, 3};
    std::string indexBytes(meshopt_encodeIndexSequenceBound(6, 4), '\0');
    indexBytes.resize(meshopt_encodeIndexSequence(reinterpret_cast<unsigned char*>(&indexBytes[0]), indexBytes.size(),
                                                  sequence.data(), 6));
    int i = m.g.accessor(m.compressed(indexBytes, 24, R"("byteStride": 4, "mode": "INDICES", "count": 6)"), kUnsignedInt, "SCALAR", 6);
    Scene scene;
    load(scene, "c.gltf", m.finish(R"({"attributes": {"POSITION": )" + std::to_string(p) + R"(, "NORMAL": )" + std::to_string(n) +
                                   R"(}, "indices": )" + std::to_string(i) + "}"));
    ASSERT_EQ(scene.triangles.size(), 2u);
    const TriangleAttributes& a = scene.triangleAttributes[scene.triangles[0].attributes];
    expectNear(octDecode(a.normal1), glm::vec3(0.6f, 0, 0.8f), 0.02f);
    expectNear(octDecode(a.normal2), glm::vec3(0, 0.6f, 0.8f), 0.02f);
}

TEST(GltfLoader, HostileMeshoptViewsAreRefusedBeforeDecoding) {
    const std::string ext = "c.gltf: /bufferViews/0/extensions/EXT_meshopt_compression";
    std::string some(64, '\x01');
    // One compressed view as the POSITION of a primitive; `claimed` overrides its compressed length.
    auto errorFor = [](const std::string& bytes, std::size_t decoded, const std::string& extension, std::size_t stride,
                       std::size_t count, std::size_t claimed = 0) {
        MeshoptGltf m;
        int v = m.compressed(bytes, decoded, extension, stride);
        if (claimed) {
            std::string& view = m.g.views[std::size_t(v)];
            std::string length = R"("byteLength": )" + std::to_string(bytes.size()) + ", \"byteStride";
            view.replace(view.rfind(length), length.size(), R"("byteLength": )" + std::to_string(claimed) + ", \"byteStride");
        }
        int p = m.g.accessor(v, kFloat, "VEC3", count);
        return errorOf("c.gltf", m.finish(R"({"attributes": {"POSITION": )" + std::to_string(p) + "}}"));
    };
    // A stride libmeshoptimizer asserts on: the asserts vanish under NDEBUG, and it would run out of bounds.
    EXPECT_EQ(errorFor(some, 18, R"("byteStride": 6, "mode": "ATTRIBUTES", "count": 3)", 0, 1),
              ext + ": ATTRIBUTES byteStride 6 is not a multiple of 4 in [4, 256]");
    EXPECT_EQ(errorFor(some, 48, R"("byteStride": 12, "mode": "TRIANGLES", "count": 4)", 12, 1),
              ext + ": TRIANGLES count 4 is not a multiple of 3");
    EXPECT_EQ(errorFor(some, 36, R"("byteStride": 12, "mode": "ATTRIBUTES", "filter": "OCTAHEDRAL", "count": 3)", 12, 3),
              ext + ": byteStride 12 does not suit the filter");
    // Sizes that disagree with the view, or that the compressed bytes could not hold.
    EXPECT_EQ(errorFor(some, 24, R"("byteStride": 12, "mode": "ATTRIBUTES", "count": 3)", 12, 2),
              ext + ": 3 elements of 12 bytes are not the buffer view's byteLength of 24");
    EXPECT_EQ(errorFor(some, 12000000, R"("byteStride": 12, "mode": "ATTRIBUTES", "count": 1000000)", 12, 3),
              ext + ": 1000000 elements cannot come from 64 compressed bytes");
    // A compressed range beyond the real buffer.
    EXPECT_EQ(errorFor(some, 36, R"("byteStride": 12, "mode": "ATTRIBUTES", "count": 3)", 12, 3, 100000),
              ext + ": extends beyond its buffer of 64 bytes");
    EXPECT_EQ(errorFor(some, 36, R"("byteStride": 12, "mode": "VERTICES", "count": 3)", 12, 3),
              ext + "/mode: unknown mode 'VERTICES' (expected ATTRIBUTES|TRIANGLES|INDICES)");
    EXPECT_EQ(errorFor(some, 36, R"("byteStride": 12, "mode": "ATTRIBUTES", "count": 3)", 12, 3).rfind(ext + ": not meshopt-compressed data", 0), 0u);
    // A plain view of the fallback buffer, which has no bytes.
    MeshoptGltf m;
    m.g.data = "data";
    m.fallbackLength = 36;
    m.g.views.push_back(R"({"buffer": 1, "byteOffset": 0, "byteLength": 36})");
    int p = m.g.accessor(0, kFloat, "VEC3", 3);
    EXPECT_EQ(errorOf("c.gltf", m.finish(R"({"attributes": {"POSITION": )" + std::to_string(p) + "}}")),
              "c.gltf: /bufferViews/0: buffer 1 is an EXT_meshopt_compression fallback, which has no data");
}

// ---- KHR_draco_mesh_compression -------------------------------------------------------------------

// A quad (two triangles) with normals, encoded by libdraco's own encoder, as a glTF whose accessors
// have no buffer views (the Draco data stands for them) and whose faces need no index data.
struct DracoGltf {
    std::string encoded;
    std::uint32_t positionId = 0;
    std::uint32_t normalId = 0;
    std::size_t points = 0;

    DracoGltf() {
        draco::TriangleSoupMeshBuilder builder;
        builder.Start(2);
        int position = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
        int normal = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
        const float corners[4][3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {2, 2, 0}};
        const float up[3] = {0, 0, 1};
        builder.SetAttributeValuesForFace(position, draco::FaceIndex(0), corners[0], corners[1], corners[2]);
        builder.SetAttributeValuesForFace(position, draco::FaceIndex(1), corners[2], corners[1], corners[3]);
        for (int f = 0; f < 2; ++f) {
            builder.SetAttributeValuesForFace(normal, draco::FaceIndex(f), up, up, up);
        }
        std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
        positionId = mesh->attribute(position)->unique_id();
        normalId = mesh->attribute(normal)->unique_id();
        points = mesh->num_points();
        draco::Encoder encoder;
        encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
        draco::EncoderBuffer buffer;
        EXPECT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &buffer).ok());
        encoded.assign(buffer.data(), buffer.size());
    }

    std::string text(const std::string& bytes, std::size_t positionCount = 0) const {
        GltfBuilder g;
        int view = g.view(bytes);
        int position = g.accessor(-1, kFloat, "VEC3", positionCount ? positionCount : points);
        int normal = g.accessor(-1, kFloat, "VEC3", points);
        int index = g.accessor(-1, kUnsignedShort, "SCALAR", 6);
        g.parts["extensionsUsed"] = R"(["KHR_draco_mesh_compression"])";
        g.parts["extensionsRequired"] = R"(["KHR_draco_mesh_compression"])";
        return g.text(R"({"attributes": {"POSITION": )" + std::to_string(position) + R"(, "NORMAL": )" + std::to_string(normal) +
                      R"(}, "indices": )" + std::to_string(index) + R"(, "extensions": {"KHR_draco_mesh_compression": {"bufferView": )" +
                      std::to_string(view) + R"(, "attributes": {"POSITION": )" + std::to_string(positionId) + R"(, "NORMAL": )" +
                      std::to_string(normalId) + "}}}}");
    }
};

TEST(GltfLoader, DracoPrimitivesDecodeWithLibdraco) {
    DracoGltf d;
    Scene scene;
    load(scene, "d.gltf", d.text(d.encoded));
    ASSERT_EQ(scene.triangles.size(), 2u);
    float area = 0.0f;
    for (const Triangle& t : scene.triangles) {
        for (glm::vec3 v : {t.v0, t.v1, t.v2}) {
            EXPECT_TRUE((std::abs(v.x) < 1e-3f || std::abs(v.x - 2) < 1e-3f) && (std::abs(v.y) < 1e-3f || std::abs(v.y - 2) < 1e-3f));
        }
        area += 0.5f * glm::length(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
        expectNear(octDecode(scene.triangleAttributes[t.attributes].normal0), glm::vec3(0, 0, 1), 1e-3f);
    }
    EXPECT_NEAR(area, 4.0f, 1e-3f);
}

TEST(GltfLoader, BadDracoDataIsOneMessage) {
    DracoGltf d;
    const std::string here = "d.gltf: /meshes/0/primitives/0/extensions/KHR_draco_mesh_compression";
    EXPECT_EQ(errorOf("d.gltf", d.text(d.encoded.substr(0, d.encoded.size() / 2))).rfind(here + ": not a Draco mesh", 0), 0u);
    EXPECT_EQ(errorOf("d.gltf", d.text("DRACO but not really")).rfind(here + ": not a Draco mesh", 0), 0u);
    EXPECT_EQ(errorOf("d.gltf", d.text(d.encoded, d.points + 1)),
              "d.gltf: /accessors/0: count " + std::to_string(d.points + 1) + ", but the Draco mesh has " +
                  std::to_string(d.points) + " points");
    std::string text = d.text(d.encoded);
    std::string id = R"("POSITION": )" + std::to_string(d.positionId) + ",";
    text.replace(text.rfind(id), id.size(), R"("POSITION": 9,)");
    EXPECT_EQ(errorOf("d.gltf", text), here + "/attributes/POSITION: the Draco mesh has no attribute 9");
    text = d.text(d.encoded);
    text.replace(text.find(R"({"bufferView": 0, "attributes")"), 16, R"({"bufferView": 7)");
    EXPECT_EQ(errorOf("d.gltf", text), here + "/bufferView: buffer view 7 does not exist");
}

// ---- Files with nothing to render -----------------------------------------------------------------

TEST(GltfLoader, NoTrianglesIsAnErrorThatSaysWhy) {
    const std::string none = "n.gltf: no triangles: ";
    {
        Gltf g;
        g.parts["meshes"] = R"([{"primitives": [{"attributes": {"POSITION": 0}, "mode": 0}, {"attributes": {"POSITION": 0}, "mode": 1}]}])";
        EXPECT_EQ(errorOf("n.gltf", g.text()), none + "its primitives are points or lines only");
    }
    {
        Gltf g;
        g.parts.erase("scene");
        g.parts.erase("scenes");
        g.parts["nodes"] = "[]";
        EXPECT_EQ(errorOf("n.gltf", g.text()), none + "the file has no nodes");
    }
    {
        Gltf g;
        g.parts["scenes"] = R"([{"nodes": []}])";
        EXPECT_EQ(errorOf("n.gltf", g.text()), none + "its scene has no nodes");
    }
    {
        Gltf g;
        g.parts["nodes"] = R"([{"name": "empty"}])";
        EXPECT_EQ(errorOf("n.gltf", g.text()), none + "none of its nodes has a mesh");
    }
    {
        Gltf g;
        g.parts["meshes"] = R"([{"primitives": {"attributes": {"POSITION": 0}}}])";
        EXPECT_EQ(errorOf("n.gltf", g.text()), none + "its meshes have no primitives");
    }
    {
        Gltf g;
        g.indices = {0, 1};
        EXPECT_EQ(errorOf("n.gltf", g.text()), none + "its triangle primitives have fewer than 3 vertices");
    }
    {
        Gltf g;
        g.positions = {0, 0, 0, 1, 0, 0, 2, 0, 0};  // on a line
        EXPECT_EQ(errorOf("n.gltf", g.text()), none + "all 1 have no area or are not finite");
    }
    EXPECT_EQ(errorOf("z.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"), "z.obj: no triangles: all 1 have no area or are not finite");
}

TEST(GltfLoader, Gltf1IsNamed) {
    EXPECT_EQ(errorOf("old.gltf", R"({"asset": {"version": "1.0"}, "meshes": {"box": {"primitives": []}}})"),
              "old.gltf: a glTF 1.0 file; Photon reads glTF 2.0");
    EXPECT_EQ(errorOf("old.gltf", R"({"asset": {"version": 1}, "meshes": {}})"), "old.gltf: a glTF 1.0 file; Photon reads glTF 2.0");
    EXPECT_EQ(errorOf("old.gltf", R"({"meshes": {"box": {}}, "nodes": {}})"), "old.gltf: a glTF 1.0 file; Photon reads glTF 2.0");
    std::string json = R"({"asset": {"version": "1.0"}})";
    std::string glb = "glTF";
    for (std::uint32_t w : {1u, std::uint32_t(20 + json.size()), std::uint32_t(json.size()), 0u}) {
        glb.append(reinterpret_cast<const char*>(&w), 4);  // version 1 (its chunk header differs from 2.0's)
    }
    EXPECT_EQ(errorOf("old.glb", glb + json), "old.glb: a glTF 1.0 binary file; Photon reads glTF 2.0");
}

// ---- The files a model names ---------------------------------------------------------------------

// Real files in a fresh folder: symbolic links and `..` are the file system's to resolve.
struct TempTree {
    std::filesystem::path root = std::filesystem::temp_directory_path() / ("photon-paths-" + std::to_string(::getpid()));

    TempTree() { std::filesystem::create_directories(root); }
    ~TempTree() { std::filesystem::remove_all(root); }

    std::string write(const std::string& name, const std::string& bytes) const {
        std::filesystem::path file = root / name;
        std::filesystem::create_directories(file.parent_path());
        std::ofstream(file, std::ios::binary) << bytes;
        return file.string();
    }
};

std::string fileErrorOf(const std::string& path, const PathPolicy& paths = {}) {
    try {
        Scene scene;
        ModelOptions options;
        options.paths = paths;
        addModelFile(scene, path, options);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(loaded)";
}

TEST(ModelPaths, NamedFilesStayInTheModelsFolderTree) {
    TempTree t;
    t.write("secret.mtl", "newmtl s\nKd 1 0 0\n# SECRET 123456\n");
    t.write("models/mb/other.mtl", "newmtl s\nKd 1 0 0\n");
    t.write("models/m/sub/inside.mtl", "newmtl s\nKd 0 1 0\n");
    std::string outside = t.write("models/m/outside.obj", std::string("mtllib ../../secret.mtl\nusemtl s\n") + kTriangleObj);
    std::string sibling = t.write("models/m/sibling.obj", std::string("mtllib ../mb/other.mtl\nusemtl s\n") + kTriangleObj);
    std::string folded = t.write("models/m/folded.obj", std::string("mtllib sub/../sub/./inside.mtl\nusemtl s\n") + kTriangleObj);
    std::filesystem::create_symlink(t.root / "secret.mtl", t.root / "models/m/link.mtl");
    std::string linked = t.write("models/m/linked.obj", std::string("mtllib link.mtl\nusemtl s\n") + kTriangleObj);

    std::string e = fileErrorOf(outside);
    EXPECT_EQ(e, outside + ": mtllib " + quote((t.root / "secret.mtl").string()) +
                     " lies outside the model's folder (--allow-outside-paths reads it)");
    EXPECT_EQ(e.find("SECRET"), std::string::npos);
    // (the paths themselves may hold any digits: a temporary folder's random name)
    std::string words = e;
    for (const std::string& path : {quote((t.root / "secret.mtl").string()), outside}) {
        words.erase(words.find(path), path.size());
    }
    EXPECT_EQ(words.find("35"), std::string::npos) << "nor its size";
    EXPECT_NE(fileErrorOf(sibling).find("lies outside the model's folder"), std::string::npos)
        << "/models/mb is not inside /models/m: components are compared, not characters";
    EXPECT_NE(fileErrorOf(linked).find("lies outside the model's folder"), std::string::npos) << "symbolic links are followed";
    EXPECT_EQ(fileErrorOf(folded), "(loaded)");
    EXPECT_EQ(fileErrorOf(outside, PathPolicy{true}), "(loaded)");
    EXPECT_EQ(fileErrorOf(linked, PathPolicy{true}), "(loaded)");
}

TEST(ModelPaths, GltfBuffersAndImagesToo) {
    TempTree t;
    Gltf g;
    std::string text = g.text();
    std::size_t uri = text.find("data:application/octet-stream;base64,");
    text.replace(uri, text.find('"', uri) - uri, "../mesh.bin");
    t.write("mesh.bin", g.data());
    std::string model = t.write("m/model.gltf", text);
    EXPECT_EQ(fileErrorOf(model).rfind(model + ": file '", 0), 0u) << fileErrorOf(model);
    EXPECT_NE(fileErrorOf(model).find("lies outside the model's folder"), std::string::npos);
    EXPECT_EQ(fileErrorOf(model, PathPolicy{true}), "(loaded)");

    Gltf image;
    image.parts["materials"] = R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}])";
    image.parts["textures"] = R"([{"source": 0}])";
    image.parts["images"] = R"([{"uri": "../../tex.png"}])";
    t.write("tex.png", twoTexelPng());
    std::string textured = t.write("a/b/model.gltf", image.text());
    EXPECT_NE(fileErrorOf(textured).find("lies outside the model's folder"), std::string::npos) << fileErrorOf(textured);
    EXPECT_EQ(fileErrorOf(textured, PathPolicy{true}), "(loaded)");
}

// Models written on Windows name their files with backslashes.
TEST(ModelPaths, BackslashesAreSeparators) {
    Files files;
    files.files["m/mat.mtl"] = "newmtl a\nmap_Kd .\\tex.png\nnewmtl b\nmap_Kd textures\\wood.png\n";
    files.files["m/tex.png"] = twoTexelPng();
    files.files["m/textures/wood.png"] = twoTexelPng();
    Scene scene;
    load(scene, "m/w.obj", "mtllib mat.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 2 3\n", files);
    ASSERT_EQ(scene.triangles.size(), 2u);
    EXPECT_NE(scene.materials[scene.triangles[0].material].albedoTexture, NONE);
    EXPECT_NE(scene.materials[scene.triangles[1].material].albedoTexture, NONE);
    EXPECT_EQ(namedFile("m/", "..\\x\\.\\y.png"), "x/y.png");
}

// ---- Messages -------------------------------------------------------------------------------------

TEST(ModelMessages, ByteOrderMarkIsNotPartOfTheFirstLine) {
    Scene scene;
    load(scene, "bom.obj", std::string("\xEF\xBB\xBF") + kTriangleObj);
    EXPECT_EQ(scene.triangles.size(), 1u);
    Files files;
    files.files["bom.mtl"] = "\xEF\xBB\xBFnewmtl red\nKd 1 0 0\n";
    Scene withMtl;
    load(withMtl, "bom.obj", std::string("mtllib bom.mtl\nusemtl red\n") + kTriangleObj, files);
    expectNear(withMtl.materials[withMtl.triangles[0].material].albedo, glm::vec3(1, 0, 0));
}

TEST(ModelMessages, LongTokensAreCut) {
    std::string digits(100000, '9');
    std::string e = errorOf("long.obj", "v " + digits + " 0 0\n");
    EXPECT_EQ(e, "long.obj: line 1: '" + std::string(40, '9') + "...' is not a finite number");
    e = errorOf("long.obj", std::string(kTriangleObj) + "f 1 2 " + digits + "\n");
    EXPECT_LT(e.size(), 200u);
}

// stb_image gives up on such a header with "unknown image type"; the header says how large it is.
TEST(ModelMessages, HugeImagesSayTheirSize) {
    std::string png = twoTexelPng();
    for (int i = 0; i < 2; ++i) {
        std::uint32_t big = 100000;
        for (int b = 0; b < 4; ++b) {
            png[std::size_t(16 + 4 * i + b)] = char((big >> (24 - 8 * b)) & 0xff);
        }
    }
    Files files;
    files.files["a.mtl"] = "newmtl t\nmap_Kd huge.png\n";
    files.files["huge.png"] = png;
    EXPECT_EQ(errorOf("a.obj", std::string("mtllib a.mtl\nusemtl t\n") + kTriangleObj, files),
              "huge.png: image of 100000x100000 texels; at most 8192 a side");
}

}  // namespace
}  // namespace photon
