// The files a model names stay in its folder tree (PathPolicy), and the loaders' messages are
// readable: no byte-order mark, long tokens cut, huge images saying their size.
#include "model_test_files.h"

namespace photon {
namespace {

using namespace test_models;

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
