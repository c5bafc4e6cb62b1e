// OBJ + MTL land in the Scene as docs/scenes.md says (geometry under its transforms, the MTL
// material table, textures decoded to linear), and every bad file is one InputError naming the
// file, the line and the reason.
#include "model_test_files.h"

namespace photon {
namespace {

using namespace test_models;

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

// Windows exporters write `mtllib sub\ok.mtl`: the `\` is a separator, as in map_Kd, not
// tinyobjloader's escape (which still escapes a space in a name).
TEST(ObjLoader, MtllibReadsABackslashAsASeparator) {
    Files files;
    files.files["sub/ok.mtl"] = "newmtl red\nKd 1 0 0\n";
    files.files["my file.mtl"] = "newmtl blue\nKd 0 0 1\n";
    Scene scene;
    load(scene, "a.obj", "mtllib sub\\ok.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", files);
    expectNear(scene.materials[scene.triangles[0].material].albedo, glm::vec3(1.0f, 0.0f, 0.0f), 1e-6f);
    Scene spaced;
    load(spaced, "b.obj", "  mtllib my\\ file.mtl\nusemtl blue\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", files);
    expectNear(spaced.materials[spaced.triangles[0].material].albedo, glm::vec3(0.0f, 0.0f, 1.0f), 1e-6f);
}

// A model's emissive surfaces light it alone only if they carry most of the power (issue 38:
// ClearCoatTest's glowing labels dropped the studio lights and left the spheres black).
TEST(ObjLoader, WeakEmittersKeepTheStudioLightsStrongOnesReplaceThem) {
    Files files;
    // A 10 × 10 floor and a 0.1 × 0.1 label of radiance 1; then the label as a bright panel.
    files.files["weak.mtl"] = "newmtl floor\nKd 0.8 0.8 0.8\nnewmtl label\nKd 0 0 0\nKe 1 1 1\n";
    files.files["strong.mtl"] = "newmtl floor\nKd 0.8 0.8 0.8\nnewmtl label\nKd 0 0 0\nKe 50 50 50\n";
    auto model = [](const char* mtl, float labelSize) {
        char text[512];
        std::snprintf(text, sizeof text,
                      "mtllib %s\nv -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nv 0 1 0\nv %g 1 0\nv %g 1 %g\nv 0 1 %g\n"
                      "usemtl floor\nf 1 4 3 2\nusemtl label\nf 5 8 7 6\n",
                      mtl, labelSize, labelSize, labelSize, labelSize);
        return std::string(text);
    };
    auto lights = [](const Scene& scene) {
        std::vector<std::uint32_t> types;
        for (const Light& l : scene.lights) {
            types.push_back(l.type);
        }
        return types;
    };
    Scene weak = loadModelScene("weak.obj", model("weak.mtl", 0.1f), files.reader());
    EXPECT_NE(weak.environmentLight, NONE) << "the studio environment lights a model with a glowing label";
    std::vector<std::uint32_t> w = lights(weak);
    EXPECT_NE(std::find(w.begin(), w.end(), LIGHT_DIRECTIONAL), w.end()) << "and the sun";
    EXPECT_NE(std::find(w.begin(), w.end(), LIGHT_TRIANGLES), w.end()) << "the label still emits";
    Scene strong = loadModelScene("strong.obj", model("strong.mtl", 8.0f), files.reader());
    EXPECT_EQ(strong.environmentLight, NONE) << "a panel of 50 over 64 m² outshines the studio: its light alone";
    EXPECT_EQ(lights(strong), std::vector<std::uint32_t>{LIGHT_TRIANGLES});
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

}  // namespace
}  // namespace photon
