// Model loader tests: OBJ + MTL and glTF land in the Scene as docs/scenes.md says (geometry under
// its transforms, the material table, textures decoded to linear, cameras and lights in their
// units), and every kind of bad file is one InputError naming the file, the place and the reason.
#include "core/model_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "core/image.h"
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

TEST(ObjLoader, BadFilesNameTheLineAndTheReason) {
    EXPECT_EQ(errorOf("b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
              "b.obj: line 4: vertex index '4' out of range (3 defined before this line)");
    EXPECT_EQ(errorOf("b.obj", "v 0 0 0\nv nan 0 0\n"), "b.obj: line 2: 'nan' is not a finite number");
    EXPECT_EQ(errorOf("b.obj", "v 0 0 0\nv 1e39 0 0\n"), "b.obj: line 2: '1e39' is not a finite number");
    EXPECT_EQ(errorOf("b.obj", "v 0 0\n"), "b.obj: line 1: v needs 3 numbers");
    EXPECT_EQ(errorOf("b.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"), "b.obj: line 3: a face needs 3 corners or more");
    EXPECT_EQ(errorOf("b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n"),
              "b.obj: line 4: texture coordinate index '1' out of range (0 defined before this line)");
    EXPECT_EQ(errorOf("b.obj", "v 0 0 0\n"), "b.obj: no faces");
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
    std::string meshes = "[";
    std::string nodes = "[";
    std::string roots = "[";
    for (int i = 0; i < 6; ++i) {
        std::string n = std::to_string(i);
        meshes += (i ? "," : "") + std::string(R"({"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": )") + n + "}]}";
        nodes += (i ? "," : "") + std::string(R"({"mesh": )") + n + "}";
        roots += (i ? "," : "") + n;
    }
    g.parts["meshes"] = meshes + "]";
    g.parts["nodes"] = nodes + "]";
    g.parts["scenes"] = R"([{"nodes": )" + roots + "]}]";
    Scene scene;
    load(scene, "mat.gltf", g.text());
    ASSERT_EQ(scene.triangles.size(), 6u);
    auto material = [&](int i) { return scene.materials[scene.triangles[std::size_t(i)].material]; };
    EXPECT_EQ(material(0).type, MATERIAL_DIFFUSE);
    expectNear(material(0).albedo, glm::vec3(0.5f, 0.25f, 0.125f));
    EXPECT_EQ(material(1).type, MATERIAL_MIRROR);
    expectNear(material(1).specular, glm::vec3(0.9f, 0.8f, 0.7f));
    EXPECT_EQ(material(2).type, MATERIAL_GLOSSY);
    expectNear(material(2).specular, glm::vec3(0.9f, 0.8f, 0.7f));
    expectNear(material(2).albedo, glm::vec3(0.0f));
    EXPECT_NEAR(material(2).roughness, 0.25f, 1e-6f);  // α = roughness²
    EXPECT_EQ(material(3).type, MATERIAL_GLASS);
    EXPECT_FLOAT_EQ(material(3).ior, 1.7f);
    expectNear(material(4).emission, glm::vec3(4, 2, 1));
    EXPECT_EQ(material(5).type, MATERIAL_GLOSSY);  // a dielectric coat over the base colour
    expectNear(material(5).specular, glm::vec3(0.04f));
    expectNear(material(5).albedo, glm::vec3(0.48f));
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
    expectNear(scene.lights[1].edgeU, glm::vec3(10.0f), 1e-4f);
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
        g.parts["extensionsRequired"] = R"(["KHR_draco_mesh_compression"])";
        g.parts["extensionsUsed"] = R"(["KHR_draco_mesh_compression"])";
        EXPECT_EQ(errorOf("b.gltf", g.text()),
                  "b.gltf: /extensionsRequired/0: the required extension 'KHR_draco_mesh_compression' is not supported");
    }
    {
        Gltf g;
        g.parts["meshes"] = R"([{"primitives": [{"attributes": {"POSITION": 7}}]}])";
        EXPECT_EQ(errorOf("b.gltf", g.text()), "b.gltf: /meshes/0/primitives/0: accessor 7 does not exist");
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
    EXPECT_EQ(errorOf("b.glb", "glTF\x02\0\0\0 truncated").rfind("b.glb: ", 0), 0u);
    EXPECT_EQ(errorOf("b.gltf", "{not json").rfind("b.gltf: ", 0), 0u);
}

// ---- Messages -------------------------------------------------------------------------------------

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
