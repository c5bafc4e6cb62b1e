// Quantized, meshopt- and Draco-compressed glTF, built view by view here (with
// libmeshoptimizer's and libdraco's encoders): each decodes to the triangles of its plain twin, and
// hostile views and data are one InputError naming the JSON pointer and the reason.
#include "model_test_files.h"

namespace photon {
namespace {

using namespace test_models;

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

}  // namespace
}  // namespace photon
