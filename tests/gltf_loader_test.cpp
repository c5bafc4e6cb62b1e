// glTF lands in the Scene as docs/scenes.md says (the node hierarchy, materials and their
// extensions, textures, cameras and punctual lights in Photon's units), and every bad file is one
// InputError naming the JSON pointer and the reason. Quantized and compressed data:
// gltf_compression_test.cpp.
#include "model_test_files.h"

namespace photon {
namespace {

using namespace test_models;

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

// KHR_materials_dispersion on a volume (thin walls do not disperse: the extension applies to
// volumes only), and KHR_materials_dispersion among the required extensions.
TEST(GltfLoader, DispersionOfVolumes) {
    Gltf g;
    g.parts["extensionsUsed"] = R"(["KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_dispersion"])";
    g.parts["extensionsRequired"] = R"(["KHR_materials_dispersion"])";
    g.parts["materials"] = R"([
        {"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_volume": {"thicknessFactor": 1},
                        "KHR_materials_dispersion": {"dispersion": 0.5}}},
        {"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_dispersion": {"dispersion": 0.5}}}])";
    g.trianglePerMaterial(2);
    Scene scene;
    load(scene, "d.gltf", g.text());
    ASSERT_EQ(scene.triangles.size(), 2u);
    EXPECT_FLOAT_EQ(scene.materials[scene.triangles[0].material].dispersion, 0.5f);
    EXPECT_EQ(scene.materials[scene.triangles[1].material].dispersion, 0.0f);
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

// KHR_materials_volume_scatter (proposed): the attenuation becomes the extinction of a medium
// inside, split by the single-scattering albedo of Kulla and Conty's fit (multiscatterColor 0: none
// scatters, 1: all does); a volume without attenuation stays clear.
TEST(GltfLoader, VolumeScatterMakesAMedium) {
    Gltf g;
    g.parts["extensionsUsed"] = R"(["KHR_materials_volume", "KHR_materials_transmission", "KHR_materials_volume_scatter"])";
    g.parts["materials"] = R"([
        {"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                        "KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 2,
                                                 "attenuationColor": [0.5, 0.5, 0.5]},
                        "KHR_materials_volume_scatter": {"multiscatterColor": [0, 1, 0.5], "scatterAnisotropy": 0.4}}},
        {"extensions": {"KHR_materials_volume": {"thicknessFactor": 1},
                        "KHR_materials_volume_scatter": {"multiscatterColor": [1, 1, 1]}}}])";
    g.trianglePerMaterial(2);
    Scene scene;
    load(scene, "scatter.gltf", g.text());
    scene.finalize();
    const Material& milky = scene.materials[scene.triangles[0].material];
    ASSERT_NE(milky.medium, NONE);
    EXPECT_EQ(milky.attenuation, glm::vec3(0.0f)) << "the medium absorbs instead";
    const Medium& md = scene.media[milky.medium];
    const float sigmaT = std::log(2.0f) / 2.0f;
    EXPECT_NEAR(md.scattering.x, 0.0f, 1e-5f);
    EXPECT_NEAR(md.absorption.x, sigmaT, 1e-5f);
    EXPECT_NEAR(md.scattering.y, sigmaT, 1e-4f);
    EXPECT_NEAR(md.absorption.y, 0.0f, 1e-4f);
    EXPECT_GT(md.scattering.z / sigmaT, 0.8f) << "a multi-scatter albedo of 0.5 needs a single-scatter one near 0.9";
    EXPECT_NEAR(md.scattering.z + md.absorption.z, sigmaT, 1e-5f);
    EXPECT_FLOAT_EQ(md.g, 0.4f);
    EXPECT_EQ(scene.materials[scene.triangles[1].material].medium, NONE);
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
    // KHR_materials_dispersion: a number from 0 (20 / Abbe number); anything else by name.
    for (const char* value : {"-1", "21", "1e300", "\"high\"", "[1]", "{\"v\": 1}", "true"}) {
        Gltf g;
        g.parts["extensionsUsed"] = R"(["KHR_materials_dispersion", "KHR_materials_volume"])";
        g.parts["materials"] = std::string(R"([{"extensions": {"KHR_materials_volume": {"thicknessFactor": 1},
                                                "KHR_materials_dispersion": {"dispersion": )") + value + "}}}]";
        g.parts["meshes"] = R"([{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}])";
        EXPECT_EQ(errorOf("b.gltf", g.text()), "b.gltf: /materials/0/extensions/KHR_materials_dispersion/dispersion: "
                                               "must be a number from 0 to 20 (20 / Abbe number)")
            << value;
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

// ---- What the pre-pass refuses (gltf_document.cpp, gltf_schema.cpp) --------------------------------

// The glTF of `g` with its one buffer given this uri and byteLength.
std::string withBuffer(const Gltf& g, const std::string& uri, std::size_t byteLength) {
    std::string text = g.text();
    std::size_t begin = text.find(R"("buffers": [)");
    std::size_t end = text.find("}]", begin) + 2;
    return text.replace(begin, end - begin,
                        R"("buffers": [{"byteLength": )" + std::to_string(byteLength) + R"(, "uri": ")" + uri + "\"}]");
}

TEST(GltfLoader, DataUrisAreCheckedAndNeverQuotedWhole) {
    Gltf g;
    const std::string data = g.data();
    const std::string prefix = "data:application/octet-stream;base64,";
    const std::string where = "b.gltf: /buffers/0/uri: ";
    EXPECT_EQ(errorOf("b.gltf", withBuffer(g, prefix + base64(data), data.size() + 1)),
              where + "the data URI holds " + std::to_string(data.size()) + " bytes, byteLength says " +
                  std::to_string(data.size() + 1));
    EXPECT_EQ(errorOf("b.gltf", withBuffer(g, "data:application/octet-stream," + base64(data), data.size())),
              where + "a data URI must be base64 (data:...;base64,...)");
    std::string bad = prefix + base64(data);
    bad[prefix.size() + 10] = '!';
    EXPECT_EQ(errorOf("b.gltf", withBuffer(g, bad, data.size())),
              where + "the data URI's base64 has a bad character '!' at byte " + std::to_string(prefix.size() + 10));
    EXPECT_EQ(errorOf("b.gltf", withBuffer(g, prefix + "QUJD" + "Q", 3)), where + "the data URI's base64 ends in the middle of a byte");
    EXPECT_EQ(errorOf("b.gltf", withBuffer(g, prefix, 1)), where + "the data URI holds no bytes");
    // Megabytes of data URI: the message stays one short line (tinygltf's quoted all of it).
    std::string big = data + std::string(3 << 20, '\x7f');
    std::string bigUri = prefix + base64(big);
    std::string e = errorOf("b.gltf", withBuffer(g, bigUri, big.size() + 1));
    EXPECT_EQ(e, where + "the data URI holds " + std::to_string(big.size()) + " bytes, byteLength says " +
                     std::to_string(big.size() + 1));
    bigUri[bigUri.size() / 2] = '#';
    e = errorOf("b.gltf", withBuffer(g, bigUri, big.size()));
    EXPECT_EQ(e, where + "the data URI's base64 has a bad character '#' at byte " + std::to_string(bigUri.size() / 2));
    e = errorOf("b.gltf", withBuffer(g, "data:application/octet-stream," + std::string(4 << 20, 'A'), big.size()));
    EXPECT_EQ(e, where + "a data URI must be base64 (data:...;base64,...)");
    EXPECT_LT(e.size(), 1000u);
    // What tinygltf itself says is cut too: here nlohmann's syntax error, which quotes the string.
    bigUri[bigUri.size() / 2] = '\x01';
    e = errorOf("b.gltf", withBuffer(g, bigUri, big.size()));
    EXPECT_EQ(e.rfind("b.gltf: ", 0), 0u) << e.substr(0, 1000);
    EXPECT_LT(e.size(), 1000u);
    {
        Gltf image;
        image.parts["images"] = R"([{"uri": "data:image/png;base64,iVBOR w0KGgo="}])";
        image.parts["textures"] = R"([{"source": 0}])";
        EXPECT_EQ(errorOf("i.gltf", image.text()), "i.gltf: /images/0/uri: the data URI's base64 has a bad character ' ' at byte 27");
    }
    // Good data URIs that tinygltf would not take as they are: another media type (or none), no
    // padding, more bytes than byteLength (the buffer is their first byteLength).
    for (const std::string& uri : {"data:;base64," + base64(data), "DATA:application/octet-stream;base64," + base64(data),
                                   "data:application/octet-stream;base64," + base64(data + "xyzw")}) {
        Scene scene;
        load(scene, "b.gltf", withBuffer(g, uri, data.size()));
        EXPECT_EQ(scene.triangles.size(), 1u) << uri.substr(0, 40);
    }
    std::string unpadded = base64(data + "xy");
    unpadded.erase(unpadded.find('='));
    Scene scene;
    load(scene, "b.gltf", withBuffer(g, "data:application/gltf-buffer;base64," + unpadded, data.size() + 2));
    EXPECT_EQ(scene.triangles.size(), 1u);
}

TEST(GltfLoader, ValuesOfTheWrongTypeAreRefusedByPointer) {
    struct Case {
        const char* member;
        const char* value;
        const char* message;
    };
    const Case cases[] = {
        {"materials", R"([{"pbrMetallicRoughness": ["not an object"]}])", "/materials/0/pbrMetallicRoughness: must be an object, not an array"},
        {"materials", R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": -1}}}])",
         "/materials/0/pbrMetallicRoughness/baseColorTexture/index: must be a non-negative integer, not -1"},
        {"materials", R"([{"normalTexture": {"index": 0, "scale": "2"}}])", "/materials/0/normalTexture/scale: must be a number, not a string"},
        {"materials", R"([{"occlusionTexture": {"index": 0, "strength": null}}])", "/materials/0/occlusionTexture/strength: must be a number, not null"},
        {"materials", R"([{"doubleSided": 1}])", "/materials/0/doubleSided: must be a boolean, not a number"},
        {"materials", R"([{"emissiveFactor": [1, "0", 0]}])", "/materials/0/emissiveFactor/1: must be a number, not a string"},
        {"materials", R"([{"emissiveTexture": {"index": 0, "extensions": {"KHR_texture_transform": "Not an object"}}}])",
         "/materials/0/emissiveTexture/extensions/KHR_texture_transform: must be an object, not a string"},
        {"materials", R"([{"emissiveTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"texCoord": 1.5}}}}])",
         "/materials/0/emissiveTexture/extensions/KHR_texture_transform/texCoord: must be a non-negative integer, not 1.5"},
        {"materials", R"([{"extensions": {"KHR_materials_ior": {"ior": "1.5"}}}])", "/materials/0/extensions/KHR_materials_ior/ior: must be a number, not a string"},
        {"materials", R"([{"extensions": {"KHR_materials_volume": {"attenuationColor": 1}}}])",
         "/materials/0/extensions/KHR_materials_volume/attenuationColor: must be an array, not a number"},
        {"materials", R"([{"extensions": {"KHR_materials_transmission": {"transmissionFactor": true}}}])",
         "/materials/0/extensions/KHR_materials_transmission/transmissionFactor: must be a number, not a boolean"},
        {"materials", R"([{"extensions": {"KHR_materials_emissive_strength": []}}])",
         "/materials/0/extensions/KHR_materials_emissive_strength: must be an object, not an array"},
        {"materials", R"([{"extensions": []}])", "/materials/0/extensions: must be an object, not an array"},
        {"materials", R"([{"name": 42}])", "/materials/0/name: must be a string, not a number"},
        {"meshes", R"([{"primitives": {"attributes": {"POSITION": 0}}}])", "/meshes/0/primitives: must be an array, not an object"},
        {"meshes", R"([{"primitives": [{"attributes": {"POSITION": "0"}}]}])", "/meshes/0/primitives/0/attributes/POSITION: must be a non-negative integer, not a string"},
        {"meshes", R"([{"primitives": [{"attributes": {"POSITION": 0}, "targets": [{"a/b~": -2}]}]}])",
         "/meshes/0/primitives/0/targets/0/a~1b~0: must be a non-negative integer, not -2"},
        {"nodes", R"([{"mesh": 0, "matrix": {}}])", "/nodes/0/matrix: must be an array, not an object"},
        {"nodes", R"([{"mesh": 0, "children": [1, 2.5]}])", "/nodes/0/children/1: must be a non-negative integer, not 2.5"},
        {"nodes", R"([{"mesh": 0.0}])", "/nodes/0/mesh: must be a non-negative integer, not 0.0"},  // tinygltf: no mesh
        {"nodes", R"([{"mesh": 0, "extensions": {"KHR_lights_punctual": {"light": -1}}}])",
         "/nodes/0/extensions/KHR_lights_punctual/light: must be a non-negative integer, not -1"},
        {"extensions", R"({"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": "bright"}]}})",
         "/extensions/KHR_lights_punctual/lights/0/intensity: must be a number, not a string"},
        {"scene", "\"0\"", "/scene: must be a non-negative integer, not a string"},
        {"scenes", R"([{"nodes": 0}])", "/scenes/0/nodes: must be an array, not a number"},
        {"asset", R"({"version": 2})", "/asset/version: must be a string, not a number"},
        {"extensionsUsed", R"([7])", "/extensionsUsed/0: must be a string, not a number"},
        {"cameras", R"([{"type": "perspective", "perspective": {"yfov": "wide"}}])", "/cameras/0/perspective/yfov: must be a number, not a string"},
        {"samplers", R"([{"wrapS": -10497}])", "/samplers/0/wrapS: must be a non-negative integer, not -10497"},
        {"textures", R"([{"source": 0.5}])", "/textures/0/source: must be a non-negative integer, not 0.5"},
        {"images", R"([{"uri": 5}])", "/images/0/uri: must be a string, not a number"},
        {"skins", R"([{"joints": [0, -1]}])", "/skins/0/joints/1: must be a non-negative integer, not -1"},
        {"animations", R"([{"channels": [{"sampler": 0, "target": {"node": 0, "path": 3}}]}])",
         "/animations/0/channels/0/target/path: must be a string, not a number"},
        {"animations", R"([{"samplers": [{"input": 0, "output": 1, "interpolation": false}]}])",
         "/animations/0/samplers/0/interpolation: must be a string, not a boolean"},
    };
    for (const Case& c : cases) {
        Gltf g;
        g.parts[c.member] = c.value;
        EXPECT_EQ(errorOf("t.gltf", g.text()), std::string("t.gltf: ") + c.message) << c.value;
    }
    // The accessors the helper writes.
    Gltf g;
    std::string text = g.text();
    text.replace(text.find(R"("count": 3)"), 10, R"("count": -3)");
    EXPECT_EQ(errorOf("t.gltf", text), "t.gltf: /accessors/0/count: must be a non-negative integer, not -3");
    // Unknown properties are glTF's to allow, whatever their type; extras are anything; the loader
    // checks what is in range.
    g.parts["materials"] = R"([{"unknown": [1], "extras": 5, "pbrMetallicRoughness": {"metallicFactor": 0, "extras": "x"}}])";
    g.parts["nodes"] = R"([{"mesh": 0, "extensions": {"EXT_other": {"anything": -1}}}])";
    Scene scene;
    load(scene, "t.gltf", g.text());
    EXPECT_EQ(scene.triangles.size(), 1u);
}

// Debian's assimp-testmodels holds one file per type a value can have wrong.
TEST(GltfLoader, AssimpWrongTypesAreRefused) {
    const std::string folder = "/usr/share/assimp/models/glTF2/wrongTypes/";
    if (!std::filesystem::exists(folder)) {
        GTEST_SKIP() << "no " << folder << " (Debian package assimp-testmodels)";
    }
    const std::pair<const char*, const char*> files[] = {
        {"badArray.gltf", "/meshes/0/primitives: must be an array, not an object"},
        {"badObject.gltf", "/materials/0/pbrMetallicRoughness: must be an object, not an array"},
        {"badUint.gltf", "/materials/0/pbrMetallicRoughness/baseColorTexture/index: must be a non-negative integer, not -1"},
        {"badNumber.gltf", "/materials/0/normalTexture/scale: must be a number, not a string"},
        {"badString.gltf", "/scenes/0/name: must be a string, not a number"},
        {"badExtension.gltf",
         "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform: must be an object, not a string"},
    };
    for (const auto& [name, message] : files) {
        std::ifstream in(folder + name, std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        EXPECT_EQ(errorOf(folder + name, bytes), folder + name + ": " + message);
    }
}

TEST(GltfLoader, AbsoluteAndRemoteUrisAreRefusedByName) {
    Gltf g;
    const std::string data = g.data();
    const std::string reason = ": absolute and remote URIs are not read; name a file relative to the model's folder";
    // JSON text: a backslash is written \\ in it.
    const std::pair<const char*, const char*> uris[] = {
        {"http://example.com/a.bin", "'http://example.com/a.bin'"},
        {"file:///tmp/a.bin", "'file:///tmp/a.bin'"},
        {"/tmp/a.bin", "'/tmp/a.bin'"},
        {"C:\\\\x.bin", "'C:\\x.bin'"},
        {"c:x.bin", "'c:x.bin'"},
        {"\\\\\\\\server\\\\a.bin", "'\\\\server\\a.bin'"},
        {"https://example.com/a-very-long-name-for-a-buffer-file-that-goes-on.bin", "'https://example.com/a-very-long-name-for...'"},
    };
    for (const auto& [uri, shown] : uris) {
        EXPECT_EQ(errorOf("d/b.gltf", withBuffer(g, uri, data.size())), std::string("d/b.gltf: /buffers/0/uri: ") + shown + reason);
    }
    Gltf image;
    image.parts["images"] = R"([{"uri": "data:image/png;base64,iVBORw0KGgo="}, {"uri": "https://example.com/t.png"}])";
    EXPECT_EQ(errorOf("i.gltf", image.text()), "i.gltf: /images/1/uri: 'https://example.com/t.png'" + reason);
    // Relative names load, Windows separators and a colon after the first segment included.
    Files files;
    files.files["d/sub/a.bin"] = data;
    files.files["d/sub/a:b.bin"] = data;
    for (const char* uri : {"sub\\\\a.bin", "sub/a.bin", "./sub/a:b.bin", "sub/a:b.bin"}) {
        Scene scene;
        load(scene, "d/b.gltf", withBuffer(g, uri, data.size()), files);
        EXPECT_EQ(scene.triangles.size(), 1u) << uri;
    }
}

TEST(GltfLoader, EmptyAndTruncatedFilesSaySo) {
    EXPECT_EQ(errorOf("e.gltf", ""), "e.gltf: empty file");
    EXPECT_EQ(errorOf("e.glb", ""), "e.glb: empty file");
    const std::string shortHeader = ": a binary glTF (.glb) shorter than its 20-byte header";
    EXPECT_EQ(errorOf("e.glb", std::string("glTF\x02\0\0\0", 8)), "e.glb" + shortHeader);
    EXPECT_EQ(errorOf("e.glb", std::string("glTF\x02\0\0\0\x40\0\0\0JSON", 16)), "e.glb" + shortHeader);
    EXPECT_EQ(errorOf("e.glb", "glT"), "e.glb" + shortHeader);
    EXPECT_EQ(errorOf("e.gltf", "glTF"), "e.gltf" + shortHeader);  // the magic says .glb, whatever the name
    EXPECT_EQ(errorOf("e.gltf", " \n").rfind("e.gltf: ", 0), 0u);
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
        g.parts["meshes"] = R"([{"primitives": []}])";
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

}  // namespace
}  // namespace photon
