// The std430/std140 layouts GLSL gives the shared structs, read back from the compiled shader by
// spirv-cross --reflect, equal the C++ layouts member by member. (The static_asserts in
// shared/layout.h pin the C++ side; this pins the GLSL side to it.)
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "shared/bindings.h"

namespace photon {
namespace {

struct Member {
    const char* type;
    const char* name;
    std::size_t offset;
};

#define PH_MEMBER(T, m) Member{#T, #m, offsetof(T, m)}

const Member kMembers[] = {
    PH_MEMBER(Sphere, center), PH_MEMBER(Sphere, radius), PH_MEMBER(Sphere, material),
    PH_MEMBER(Plane, normal), PH_MEMBER(Plane, offset), PH_MEMBER(Plane, material),
    PH_MEMBER(Quad, corner), PH_MEMBER(Quad, material), PH_MEMBER(Quad, edgeU), PH_MEMBER(Quad, area),
    PH_MEMBER(Quad, edgeV), PH_MEMBER(Quad, w),
    PH_MEMBER(Triangle, v0), PH_MEMBER(Triangle, material), PH_MEMBER(Triangle, v1), PH_MEMBER(Triangle, attributes),
    PH_MEMBER(Triangle, v2), PH_MEMBER(Triangle, flags),
    PH_MEMBER(TriangleAttributes, normal0), PH_MEMBER(TriangleAttributes, flags), PH_MEMBER(TriangleAttributes, s0),
    PH_MEMBER(TriangleAttributes, t1), PH_MEMBER(TriangleAttributes, t2), PH_MEMBER(TriangleAttributes, tangent),
    PH_MEMBER(Material, albedo), PH_MEMBER(Material, type), PH_MEMBER(Material, specular),
    PH_MEMBER(Material, roughness), PH_MEMBER(Material, emission), PH_MEMBER(Material, ior),
    PH_MEMBER(Material, albedoTexture), PH_MEMBER(Material, metallicRoughnessTexture), PH_MEMBER(Material, normalTexture),
    PH_MEMBER(Material, emissionTexture), PH_MEMBER(Material, metallic), PH_MEMBER(Material, transmission),
    PH_MEMBER(Material, alpha), PH_MEMBER(Material, alphaCutoff), PH_MEMBER(Material, attenuation),
    PH_MEMBER(Material, flags), PH_MEMBER(Material, normalScale), PH_MEMBER(Material, dispersion),
    PH_MEMBER(Material, medium),
    PH_MEMBER(Medium, absorption), PH_MEMBER(Medium, g), PH_MEMBER(Medium, scattering), PH_MEMBER(Medium, grid), PH_MEMBER(Medium, lower),
    PH_MEMBER(Medium, upper), PH_MEMBER(Medium, resolution),
    PH_MEMBER(Texture, offset), PH_MEMBER(Texture, wrap), PH_MEMBER(Texture, transformS), PH_MEMBER(Texture, transformT),
    PH_MEMBER(WideBvhNode, origin), PH_MEMBER(WideBvhNode, scales), PH_MEMBER(WideBvhNode, lowerX),
    PH_MEMBER(WideBvhNode, lowerY), PH_MEMBER(WideBvhNode, lowerZ), PH_MEMBER(WideBvhNode, kinds),
    PH_MEMBER(WideBvhNode, upperX), PH_MEMBER(WideBvhNode, upperY), PH_MEMBER(WideBvhNode, upperZ),
    PH_MEMBER(WideBvhNode, children),
    PH_MEMBER(EmissiveTriangle, triangle), PH_MEMBER(EmissiveTriangle, cdf), PH_MEMBER(EmissiveTriangle, area),
    PH_MEMBER(Light, position), PH_MEMBER(Light, type), PH_MEMBER(Light, power), PH_MEMBER(Light, extent),
    PH_MEMBER(Light, axis), PH_MEMBER(Light, spotOuter), PH_MEMBER(Light, vectorU), PH_MEMBER(Light, spotInner),
    PH_MEMBER(Light, vectorV), PH_MEMBER(Light, area), PH_MEMBER(Light, pickCdf), PH_MEMBER(Light, pickProbability),
    PH_MEMBER(Light, profile), PH_MEMBER(Light, falloffMean), PH_MEMBER(Light, emitterFirst),
    PH_MEMBER(Light, emitterCount),
    PH_MEMBER(CausticTarget, center), PH_MEMBER(CausticTarget, radius),
    PH_MEMBER(Camera, position), PH_MEMBER(Camera, lensRadius), PH_MEMBER(Camera, forward),
    PH_MEMBER(Camera, focusDistance), PH_MEMBER(Camera, right), PH_MEMBER(Camera, tanHalfFovY),
    PH_MEMBER(Camera, up), PH_MEMBER(Camera, aspect),
    PH_MEMBER(SceneInfo, planeCount), PH_MEMBER(SceneInfo, lightCount), PH_MEMBER(SceneInfo, targetCount),
    PH_MEMBER(SceneInfo, infiniteLight), PH_MEMBER(SceneInfo, bvhNodeCount), PH_MEMBER(SceneInfo, linearCount),
    PH_MEMBER(SceneInfo, environmentLight), PH_MEMBER(SceneInfo, medium),
    PH_MEMBER(GridParams, origin), PH_MEMBER(GridParams, cellSize), PH_MEMBER(GridParams, resolution),
    PH_MEMBER(GridParams, kind), PH_MEMBER(GridParams, cellCount), PH_MEMBER(GridParams, cellOffset),
    PH_MEMBER(GridParams, photonOffset), PH_MEMBER(GridParams, photonCapacity), PH_MEMBER(GridParams, radius),
    PH_MEMBER(FrameParams, camera), PH_MEMBER(FrameParams, scene), PH_MEMBER(FrameParams, grids),
    PH_MEMBER(FrameParams, width), PH_MEMBER(FrameParams, seed), PH_MEMBER(FrameParams, globalPaths),
    PH_MEMBER(FrameParams, maxEyeDepth), PH_MEMBER(FrameParams, estimator), PH_MEMBER(FrameParams, globalMode),
    PH_MEMBER(FrameParams, gatherRays), PH_MEMBER(FrameParams, flags), PH_MEMBER(FrameParams, eyeSplits),
    PH_MEMBER(FrameParams, accumulated), PH_MEMBER(FrameParams, gatherBudget), PH_MEMBER(FrameParams, alpha),
    PH_MEMBER(FrameParams, sppm), PH_MEMBER(FrameParams, pathFirst), PH_MEMBER(FrameParams, pathCount), PH_MEMBER(FrameParams, spectrum),
    PH_MEMBER(SpectralParams, wavelengths), PH_MEMBER(SpectralParams, cauchy), PH_MEMBER(SpectralParams, fromRgb0),
    PH_MEMBER(SpectralParams, fromRgb2), PH_MEMBER(SpectralParams, toRgb0), PH_MEMBER(SpectralParams, toRgb2),
    PH_MEMBER(SppmMapParams, firstRadius), PH_MEMBER(SppmMapParams, firstFootprints), PH_MEMBER(SppmMapParams, batches),
    PH_MEMBER(SppmMapParams, firstNeighbours),
    PH_MEMBER(Photon, position), PH_MEMBER(Photon, incoming), PH_MEMBER(Photon, power), PH_MEMBER(Photon, id),
    PH_MEMBER(MapPhoton, x), PH_MEMBER(MapPhoton, z), PH_MEMBER(MapPhoton, power),
    PH_MEMBER(HitPoint, position), PH_MEMBER(HitPoint, material), PH_MEMBER(HitPoint, weight),
    PH_MEMBER(HitPoint, normal), PH_MEMBER(HitPoint, direct), PH_MEMBER(HitPoint, outgoing),
    PH_MEMBER(HitPoint, albedo), PH_MEMBER(HitPoint, geometricNormal), PH_MEMBER(HitPoint, metallic),
    PH_MEMBER(HitPoint, roughness), PH_MEMBER(HitPoint, channel), PH_MEMBER(HitPoint, pathLength), PH_MEMBER(HitPoint, aovAlbedo), PH_MEMBER(HitPoint, aovNormal),
    PH_MEMBER(PixelAov, albedo), PH_MEMBER(PixelAov, depth), PH_MEMBER(PixelAov, normal), PH_MEMBER(PixelAov, coverage),
    PH_MEMBER(PixelAov, luminance), PH_MEMBER(PixelAov, luminance2), PH_MEMBER(PixelAov, background),
    PH_MEMBER(SppmPixel, direct), PH_MEMBER(SppmPixel, maps), PH_MEMBER(SppmPixel, count),
    PH_MEMBER(SppmFlux, flux), PH_MEMBER(SppmFlux, radius),
};


TEST(Layout, GlslOffsetsEqualCpp) {
    std::ifstream in(PHOTON_LAYOUT_REFLECTION);
    ASSERT_TRUE(in) << "missing " << PHOTON_LAYOUT_REFLECTION;
    nlohmann::json reflection = nlohmann::json::parse(in);
    // (struct, member) → offset, for the structs GLSL laid out in buffers.
    std::map<std::pair<std::string, std::string>, std::size_t> glsl;
    std::map<std::string, std::size_t> strides;
    for (const auto& [id, type] : reflection["types"].items()) {
        for (const auto& m : type["members"]) {
            if (m.contains("offset")) {
                glsl[{type["name"], m["name"]}] = m["offset"];
            }
            if (m.contains("array_stride")) {
                strides[m["name"]] = m["array_stride"];
            }
        }
    }
    for (const Member& m : kMembers) {
        auto it = glsl.find({m.type, m.name});
        ASSERT_NE(it, glsl.end()) << m.type << "::" << m.name << " not laid out in any GLSL buffer";
        EXPECT_EQ(it->second, m.offset) << m.type << "::" << m.name;
    }
    // Every buffer of the list (shared/bindings.h): its GLSL array stride is the C++ element size,
    // and its block has the list's binding.
    std::map<std::string, std::uint32_t> bindings;
    for (const auto& ssbo : reflection["ssbos"]) {
        bindings[ssbo["name"]] = ssbo["binding"];
    }
    for (const BufferInfo& info : kBuffers) {
        ASSERT_TRUE(strides.count(info.name)) << info.name << " is not laid out in the GLSL shader";
        EXPECT_EQ(strides[info.name], info.elementBytes) << info.name;
        std::string block = std::string(info.name) + "Buffer";
        ASSERT_TRUE(bindings.count(block)) << block;
        EXPECT_EQ(bindings[block], info.binding) << block;
    }
}

// The check files compile every shared header with nvcc and glslang (shared/README.md), so a
// header that only the CPU includes cannot hide C++ from the other two compilers.
TEST(SharedCheck, IncludesEveryHeader) {
    std::filesystem::path root = PHOTON_SOURCE_DIR;
    for (const char* check : {"cuda/shared_check.cu", "glsl/shared_check.comp"}) {
        std::ifstream in(root / check);
        ASSERT_TRUE(in) << check;
        std::stringstream text;
        text << in.rdbuf();
        for (const auto& entry : std::filesystem::directory_iterator(root / "shared")) {
            if (entry.path().extension() == ".h") {
                std::string include = "#include \"../shared/" + entry.path().filename().string() + "\"";
                EXPECT_NE(text.str().find(include), std::string::npos) << check << " does not include " << entry.path();
            }
        }
    }
}

}  // namespace
}  // namespace photon
