// Scene loader tests: every scene in scenes/ loads, values land where they belong in the Scene, and
// each kind of bad input is reported as one line "<source>: <JSON pointer or line/column>: <reason>".
#include "core/loaders/scene_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include "core/system/error.h"
#include "shared/light_types.h"
#include "test_util.h"

namespace photon {
namespace {

// A small valid scene with the top-level `key` set to `value` (added if it is none of the four
// required parts).
std::string sceneWith(const std::string& key = "", const std::string& value = "") {
    std::map<std::string, std::string> parts = {
        {"camera", R"({"position": [0, 1, 4], "look_at": [0, 1, 0]})"},
        {"materials", R"({"white": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]}})"},
        {"objects", R"([{"type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "white"}])"},
        {"lights", R"([{"type": "point", "position": [0, 3, 0], "power": 10}])"},
    };
    if (!key.empty()) {
        parts[key] = value;
    }
    std::string text;
    for (const auto& [k, v] : parts) {
        text += (text.empty() ? "{\"" : ", \"") + k + "\": " + v;
    }
    return text + "}";
}

Scene load(const std::string& text) { return loadSceneJson(text, "x.json"); }

std::string errorOf(const std::string& text) {
    try {
        load(text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(loaded)";
}

std::string objectError(const std::string& object) { return errorOf(sceneWith("objects", "[" + object + "]")); }
std::string lightError(const std::string& light) { return errorOf(sceneWith("lights", "[" + light + "]")); }
std::string renderError(const std::string& render) { return errorOf(sceneWith("render", render)); }

// ---- Valid scenes -------------------------------------------------------------------------------

TEST(SceneLoader, EveryShippedSceneLoads) {
    int count = 0;
    for (const std::string& path : test::shippedScenes({".json"})) {
        SCOPED_TRACE(path);
        Scene scene = loadSceneFile(path);
        EXPECT_FALSE(scene.lights.empty());
        ++count;
    }
    EXPECT_GT(count, 0);
}

TEST(SceneLoader, DefaultSceneIsTheCornellBox) {
    Scene embedded = defaultScene();
    Scene file = loadSceneFile(test::scenesDir() + "/cornell.json");
    EXPECT_EQ(embedded.name, file.name);
    EXPECT_EQ(embedded.quads.size(), file.quads.size());
    EXPECT_EQ(embedded.spheres.size(), file.spheres.size());
    EXPECT_EQ(embedded.materialNames, file.materialNames);
}

TEST(SceneLoader, MinimalSceneTakesDefaults) {
    Scene scene = load(sceneWith());
    EXPECT_EQ(scene.camera.fovY, 40.0f);
    EXPECT_EQ(scene.camera.up, glm::vec3(0, 1, 0));
    EXPECT_EQ(scene.environment.radiance, glm::vec3(0.0f));
    EXPECT_EQ(scene.render.width, RenderSettings{}.width);
    EXPECT_EQ(scene.lights[0].power, glm::vec3(10.0f));  // a number is the same in every channel
    EXPECT_EQ(scene.lights[0].profile, EMIT_ISOTROPIC);
}

TEST(SceneLoader, SphereValues) {
    Scene scene = load(sceneWith());
    ASSERT_EQ(scene.spheres.size(), 1u);
    EXPECT_EQ(scene.spheres[0].center, glm::vec3(0, 1, 0));
    EXPECT_EQ(scene.spheres[0].radius, 0.5f);
    EXPECT_EQ(scene.materialNames[scene.spheres[0].material], "white");
}

TEST(SceneLoader, MaterialTypes) {
    Scene scene = load(sceneWith("materials", R"({
        "white": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]},
        "coat": {"type": "reflective", "albedo": [0.5, 0.1, 0.1], "reflectance": [0.3, 0.3, 0.3]},
        "brass": {"type": "glossy", "albedo": [0.2, 0.1, 0.0], "specular": [0.7, 0.6, 0.3], "roughness": 0.2}})"));
    const Material& coat = scene.materials[scene.findMaterial("coat")];
    EXPECT_EQ(coat.type, MATERIAL_REFLECTIVE);
    EXPECT_EQ(coat.specular, glm::vec3(0.3f));
    const Material& brass = scene.materials[scene.findMaterial("brass")];
    EXPECT_EQ(brass.type, MATERIAL_GLOSSY);
    EXPECT_FLOAT_EQ(brass.roughness, 0.2f);
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"white": {"type": "reflective", "albedo": [0.8, 0.8, 0.8],
                                                            "reflectance": [0.1, 0.3, 0.1]}})")),
              "x.json: /materials/white: albedo + reflectance exceeds 1 in channel g: energy would be created");
}

TEST(SceneLoader, PbrMaterial) {
    Scene scene = load(sceneWith("materials", R"({
        "white": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]},
        "gold": {"type": "pbr", "base_color": [1, 0.8, 0.3], "metallic": 1, "roughness": 0.4},
        "green glass": {"type": "pbr", "base_color": [1, 1, 1], "roughness": 0, "transmission": 1, "ior": 1.52,
                        "attenuation_color": [0.5, 1, 1], "attenuation_distance": 2}})"));
    const Material& gold = scene.materials[scene.findMaterial("gold")];
    EXPECT_EQ(gold.type, MATERIAL_PBR);
    EXPECT_FLOAT_EQ(gold.metallic, 1.0f);
    EXPECT_FLOAT_EQ(gold.roughness, 0.16f);  // α = roughness²
    EXPECT_EQ(gold.albedoTexture, NONE);
    const Material& glass = scene.materials[scene.findMaterial("green glass")];
    EXPECT_FLOAT_EQ(glass.transmission, 1.0f);
    EXPECT_FLOAT_EQ(glass.ior, 1.52f);
    EXPECT_NEAR(glass.attenuation.x, std::log(2.0f) / 2.0f, 1e-6f);
    EXPECT_FLOAT_EQ(glass.attenuation.y, 0.0f);
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"white": {"type": "pbr", "base_color": [1, 1, 1], "ior": 0.5}})")),
              "x.json: /materials/white/ior: must be in [1, 10] (got 0.5)");
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"white": {"type": "pbr", "base_color": [1, 1, 1],
                                                            "attenuation_color": [1, 1, 1]}})")),
              "x.json: /materials/white: attenuation_color and attenuation_distance come together");
}

// Dispersion by the Abbe number: dispersion = 20 / V_d (KHR_materials_dispersion's value); a
// non-positive or non-numeric one is refused by name.
TEST(SceneLoader, AbbeNumberSetsDispersion) {
    Scene scene = load(sceneWith("materials", R"({
        "flint": {"type": "glass", "ior": 1.6, "abbe": 32},
        "gem": {"type": "pbr", "base_color": [1, 1, 1], "transmission": 1, "abbe": 20},
        "crown": {"type": "glass"}, "white": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]}})"));
    EXPECT_FLOAT_EQ(scene.materials[scene.findMaterial("flint")].dispersion, 20.0f / 32.0f);
    EXPECT_FLOAT_EQ(scene.materials[scene.findMaterial("gem")].dispersion, 1.0f);
    EXPECT_EQ(scene.materials[scene.findMaterial("crown")].dispersion, 0.0f);
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"g": {"type": "glass", "abbe": 0}})")),
              "x.json: /materials/g/abbe: must be in [1, 1e+06] (got 0)");
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"g": {"type": "glass", "abbe": -5}})")),
              "x.json: /materials/g/abbe: must be in [1, 1e+06] (got -5)");
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"g": {"type": "glass", "abbe": 1e-300}})")),
              "x.json: /materials/g/abbe: must be in [1, 1e+06] (got 1e-300)");
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"g": {"type": "glass", "abbe": "crown"}})")),
              "x.json: /materials/g/abbe: expected a number (got string)");
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"g": {"type": "diffuse", "albedo": [1, 1, 1], "abbe": 30}})")),
              "x.json: /materials/g/abbe: unknown key");
}

TEST(SceneLoader, QuadArea) {
    Scene scene = load(sceneWith("objects", R"([{"type": "quad", "corner": [0, 0, 0], "edge_u": [2, 0, 0],
                                                 "edge_v": [0, 0, 3], "material": "white"}])"));
    ASSERT_EQ(scene.quads.size(), 1u);
    EXPECT_FLOAT_EQ(scene.quads[0].area, 6.0f);
}

TEST(SceneLoader, BoxIsSixQuads) {
    Scene scene = load(sceneWith("objects", R"([{"type": "box", "min": [0, 0, 0], "max": [1, 2, 3],
                                                 "material": "white"}])"));
    ASSERT_EQ(scene.quads.size(), 6u);
    float area = 0.0f;
    for (const Quad& q : scene.quads) {
        area += q.area;
        glm::vec3 faceCenter = q.corner + 0.5f * (q.edgeU + q.edgeV);
        EXPECT_GT(glm::dot(glm::cross(q.edgeU, q.edgeV), faceCenter - glm::vec3(0.5f, 1.0f, 1.5f)), 0.0f);  // outward
    }
    EXPECT_FLOAT_EQ(area, 2.0f * (1 * 2 + 2 * 3 + 1 * 3));
}

TEST(SceneLoader, SpotLightCone) {
    Scene scene = load(sceneWith("lights", R"([{"type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0],
                                                "angle": 30, "falloff_start": 20, "power": [1, 2, 3]}])"));
    const Light& l = scene.lights[0];
    EXPECT_EQ(l.type, LIGHT_SPOT);
    EXPECT_NEAR(l.spotOuter, 1.0 - std::cos(glm::radians(30.0)), 1e-6);
    EXPECT_NEAR(l.spotInner, 1.0 - std::cos(glm::radians(20.0)), 1e-6);
    EXPECT_EQ(l.power, glm::vec3(1, 2, 3));
}

TEST(SceneLoader, AreaLightsAddTheirSurface) {
    Scene scene = load(sceneWith("lights", R"([
        {"type": "sphere", "center": [0, 3, 0], "radius": 0.25, "power": 5},
        {"type": "quad", "corner": [0, 2, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "power": 5}])"));
    EXPECT_EQ(scene.spheres.size(), 2u);
    EXPECT_EQ(scene.quads.size(), 1u);
    EXPECT_EQ(scene.materialNames.back(), "light1");
}

TEST(SceneLoader, EmittingTrianglesAreAnAreaLight) {
    std::string text = sceneWith("materials", R"({"white": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]},
        "panel": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [2, 2, 1]}})");
    text.replace(text.find("\"objects\": [") + 12, 0,
                 R"({"type": "triangle", "vertices": [[0, 2, 0], [0, 2, 1], [1, 2, 0]], "material": "panel"}, )");
    Scene scene = load(text);
    scene.finalize();
    ASSERT_EQ(scene.emissiveTriangles.size(), 1u);
    const Light& panel = scene.lights.back();
    EXPECT_EQ(panel.type, LIGHT_TRIANGLES);
    EXPECT_FLOAT_EQ(panel.power.x, 2.0f * PI * 0.5f);  // Φ = π L · area
    EXPECT_FLOAT_EQ(panel.power.z, 1.0f * PI * 0.5f);
}

TEST(SceneLoader, RenderSettingsOverrideDefaults) {
    std::string text = sceneWith("render", R"({"width": 320, "height": 200.0, "estimator": "knn", "k": 64,
                                              "tonemap": "reinhard", "seed": 4294967295, "exposure": -1.5})");
    Scene scene = load(text);
    EXPECT_EQ(scene.render.width, 320u);
    EXPECT_EQ(scene.render.height, 200u);
    EXPECT_EQ(scene.render.estimator, Estimator::Knn);
    EXPECT_EQ(scene.render.k, 64u);
    EXPECT_EQ(scene.render.tonemap, Tonemap::Reinhard);
    EXPECT_EQ(scene.render.seed, 4294967295u);
    EXPECT_EQ(scene.render.exposure, -1.5f);
}

// ---- Bad input: one test per kind, checking the whole message -----------------------------------

TEST(SceneLoaderErrors, FileCannotBeOpened) {
    try {
        loadSceneFile("/nonexistent/scene.json");
        FAIL() << "loaded";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "/nonexistent/scene.json: cannot open scene file: No such file or directory");
    }
}

TEST(SceneLoaderErrors, BrokenJsonGivesLineAndColumn) {
    EXPECT_EQ(errorOf("{\n  \"camera\": [1, 2,,]\n}"),
              "x.json: line 2, column 19: unexpected ','; expected '[', '{', or a literal");
    EXPECT_EQ(errorOf(""), "x.json: line 1, column 1: unexpected end of input; expected '[', '{', or a literal");
    EXPECT_EQ(errorOf("{} {}"), "x.json: line 1, column 4: unexpected '{'; expected end of input");
}

TEST(SceneLoaderErrors, NonFiniteNumbers) {
    EXPECT_EQ(errorOf("{\"a\": NaN}"), "x.json: line 1, column 7: invalid literal; last read: '\"a\": N'");
    EXPECT_EQ(errorOf("{\"a\":\n 1e999}"), "x.json: line 2, column 6: number overflow parsing '1e999'");
    EXPECT_EQ(objectError(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1e300, "material": "white"})"),
              "x.json: /objects/0/radius: must be a finite number within the range of a float (got 1e+300)");
}

TEST(SceneLoaderErrors, TopLevelMustBeAnObject) {
    EXPECT_EQ(errorOf("[1, 2]"), "x.json: /: expected an object (got array)");
}

TEST(SceneLoaderErrors, MissingRequiredKey) {
    EXPECT_EQ(errorOf(R"({"materials": {}, "objects": [], "lights": []})"), "x.json: /: missing required key 'camera'");
    EXPECT_EQ(objectError(R"({"type": "sphere", "center": [0, 0, 0], "material": "white"})"),
              "x.json: /objects/0: missing required key 'radius'");
}

TEST(SceneLoaderErrors, UnknownKey) {
    EXPECT_EQ(errorOf(sceneWith("camera", R"({"position": [0, 1, 4], "look_at": [0, 1, 0], "fovv": 40})")),
              "x.json: /camera/fovv: unknown key");
}

TEST(SceneLoaderErrors, WrongType) {
    EXPECT_EQ(objectError(R"({"type": "sphere", "center": [0, 0, 0], "radius": "big", "material": "white"})"),
              "x.json: /objects/0/radius: expected a number (got string)");
    EXPECT_EQ(objectError(R"({"type": "sphere", "center": [0, 0], "radius": 1, "material": "white"})"),
              "x.json: /objects/0/center: expected an array of 3 numbers");
    EXPECT_EQ(errorOf(sceneWith("objects", "{}")), "x.json: /objects: expected an array (got object)");
}

TEST(SceneLoaderErrors, OutOfRange) {
    EXPECT_EQ(objectError(R"({"type": "sphere", "center": [0, 0, 0], "radius": -1, "material": "white"})"),
              "x.json: /objects/0/radius: must be positive (got -1)");
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"red": {"type": "diffuse", "albedo": [1.2, 0, 0]}})")),
              "x.json: /materials/red/albedo/0: must be in [0, 1] (got 1.2)");
    EXPECT_EQ(errorOf(sceneWith("camera", R"({"position": [0, 1, 4], "look_at": [0, 1, 0], "fov": 180})")),
              "x.json: /camera/fov: must be in (0, 180) (got 180)");
}

TEST(SceneLoaderErrors, BadIntegers) {
    EXPECT_EQ(renderError(R"({"width": 1.5})"), "x.json: /render/width: must be an integer in [1, 16384] (got 1.5)");
    EXPECT_EQ(renderError(R"({"width": 1e9})"),
              "x.json: /render/width: must be an integer in [1, 16384] (got 1000000000.0)");
    EXPECT_EQ(renderError(R"({"seed": -1})"), "x.json: /render/seed: must be an integer in [0, 4294967295] (got -1)");
}

TEST(SceneLoaderErrors, UnknownEnumValue) {
    EXPECT_EQ(renderError(R"({"estimator": "fast"})"),
              "x.json: /render/estimator: unknown value 'fast' (expected cell|radius|knn|progressive|sppm)");
}

TEST(SceneLoaderErrors, UnknownType) {
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"gold": {"type": "metal"}})")),
              "x.json: /materials/gold/type: unknown material type 'metal' (expected diffuse|mirror|glass|glossy|reflective|pbr)");
    EXPECT_EQ(objectError(R"({"type": "cube", "material": "white"})"),
              "x.json: /objects/0/type: unknown object type 'cube' (expected sphere|plane|quad|triangle|box|mesh)");
}

TEST(SceneLoaderErrors, UnknownMaterial) {
    EXPECT_EQ(objectError(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "steel"})"),
              "x.json: /objects/0/material: unknown material 'steel'");
}

TEST(SceneLoaderErrors, OnlyTrianglesEmit) {
    std::string materials = R"({"white": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]},
        "hot": {"type": "mirror", "emission": [1, 1, 1]}})";
    std::string text = sceneWith("materials", materials);
    text.replace(text.find("\"material\": \"white\""), 19, "\"material\": \"hot\"");
    EXPECT_EQ(errorOf(text), "x.json: /objects/0/material: 'hot' emits, and only triangles and meshes emit (a sphere or "
                             "quad that shines is a light: see \"lights\")");
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"white": {"type": "diffuse", "albedo": [1, 1, 1], "emission": [-1, 0, 0]}})")),
              "x.json: /materials/white/emission/0: must be non-negative (got -1)");
}

TEST(SceneLoaderErrors, ReservedMaterialName) {
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"light0": {"type": "mirror"}})")),
              "x.json: /materials/light0: names starting with 'light' and a digit are reserved for the emitters of "
              "area lights");
}

TEST(SceneLoaderErrors, GlossyEnergy) {
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"g": {"type": "glossy", "albedo": [0.5, 0.8, 0.5],
                                                       "specular": [0.5, 0.5, 0.5], "roughness": 0.1}})")),
              "x.json: /materials/g: albedo + specular exceeds 1 in channel g: energy would be created");
}

TEST(SceneLoaderErrors, DegenerateGeometry) {
    EXPECT_EQ(objectError(R"({"type": "quad", "corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [2, 0, 0],
                              "material": "white"})"),
              "x.json: /objects/0: edge_u and edge_v are parallel or zero (area at most 1e-12)");
    EXPECT_EQ(objectError(R"({"type": "triangle", "vertices": [[0, 0, 0], [1, 1, 1], [2, 2, 2]],
                              "material": "white"})"),
              "x.json: /objects/0/vertices: degenerate triangle: the vertices are collinear or coincide");
    EXPECT_EQ(objectError(R"({"type": "box", "min": [0, 0, 0], "max": [1, 0, 1], "material": "white"})"),
              "x.json: /objects/0/max: must be greater than min on every axis");
    EXPECT_EQ(objectError(R"({"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 0], "material": "white"})"),
              "x.json: /objects/0/normal: must be non-zero");
}

TEST(SceneLoaderErrors, BadCamera) {
    EXPECT_EQ(errorOf(sceneWith("camera", R"({"position": [0, 1, 4], "look_at": [0, 1, 4]})")),
              "x.json: /camera/look_at: must differ from position");
    EXPECT_EQ(errorOf(sceneWith("camera", R"({"position": [0, 1, 4], "look_at": [0, 1, 0], "up": [0, 0, -2]})")),
              "x.json: /camera/up: must not be parallel to look_at - position");
}

TEST(SceneLoaderErrors, BadPower) {
    EXPECT_EQ(lightError(R"({"type": "point", "position": [0, 3, 0], "power": "bright"})"),
              "x.json: /lights/0/power: expected an RGB array of 3 numbers or a number");
    EXPECT_EQ(lightError(R"({"type": "point", "position": [0, 3, 0], "power": [0, 0, 0]})"),
              "x.json: /lights/0/power: must be positive in at least one channel");
}

TEST(SceneLoaderErrors, LightsTooSmallForAFloat) {
    EXPECT_EQ(lightError(R"({"type": "sphere", "center": [0, 3, 0], "radius": 1e-30, "power": 1})"),
              "x.json: /lights/0/radius: out of range: the area 4 pi r^2 must be above 1e-12 and finite as a float");
    EXPECT_EQ(lightError(R"({"type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0], "angle": 1e-30,
                             "power": 1})"),
              "x.json: /lights/0/angle: too small: 1 - cos(angle) underflows a float");
}

TEST(SceneLoaderErrors, LightCount) {
    EXPECT_EQ(errorOf(sceneWith("lights", "[]")), "x.json: /lights: the scene has no lights");
    std::string many = "[";
    for (int i = 0; i < 65; ++i) {
        many += std::string(i ? "," : "") + R"({"type": "point", "position": [0, 3, 0], "power": 1})";
    }
    EXPECT_EQ(errorOf(sceneWith("lights", many + "]")), "x.json: /lights: too many lights: 65 (at most 64)");
}

TEST(SceneLoaderErrors, LightKeysDependOnTheKind) {
    EXPECT_EQ(lightError(R"({"type": "point", "position": [0, 3, 0], "direction": [0, -1, 0], "power": 1})"),
              "x.json: /lights/0/direction: only for hemisphere emission");
    EXPECT_EQ(lightError(R"({"type": "point", "emission": "hemisphere", "position": [0, 3, 0], "power": 1})"),
              "x.json: /lights/0: missing required key 'direction'");
    EXPECT_EQ(lightError(R"({"type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0], "angle": 30,
                             "falloff_start": 40, "power": 1})"),
              "x.json: /lights/0/falloff_start: must be in [0, 30] (got 40)");
}

TEST(SceneLoaderErrors, PointersEscapeAndMessagesStayOnOneLine) {
    EXPECT_EQ(errorOf(sceneWith("materials", R"({"a/b~c": {"type": "diffuse", "albedo": [2, 0, 0]}})")),
              "x.json: /materials/a~1b~0c/albedo/0: must be in [0, 1] (got 2)");
    EXPECT_EQ(objectError(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "a\nb"})"),
              "x.json: /objects/0/material: unknown material 'a\\x0ab'");
}

// A scene without geometry used to load and fail later at frame setup, naming an option the user
// never gave ("--radius 0 (automatic)").
TEST(SceneLoaderErrors, NoGeometry) {
    EXPECT_EQ(errorOf(sceneWith("objects", "[]")),
              "x.json: /objects: the scene has no geometry: nothing for light to fall on or the camera to see");
    // A sphere or quad light is geometry of its own.
    EXPECT_EQ(errorOf(sceneWith("objects", "[]").replace(sceneWith("objects", "[]").find(R"({"type": "point")"), 0,
                                                          R"({"type": "sphere", "center": [0, 2, 0], "radius": 0.2, "power": 5}, )")),
              "(loaded)");
}

// A quoted token in a message is cut to 40 characters: a 100000-digit number is not a 100 KB line.
TEST(SceneLoaderErrors, LongTokensAreCut) {
    std::string digits(100000, '7');
    std::string e = errorOf(sceneWith("background", "[" + digits + ", 0, 0]"));
    EXPECT_LT(e.size(), 200u) << e.substr(0, 300);
    EXPECT_NE(e.find("'" + std::string(40, '7') + "...'"), std::string::npos) << e.substr(0, 300);
    e = objectError(R"({"type": ")" + std::string(5000, 'x') + R"(", "material": "white"})");
    EXPECT_EQ(e, "x.json: /objects/0/type: unknown object type '" + std::string(40, 'x') +
                     "...' (expected sphere|plane|quad|triangle|box|mesh)");
}

}  // namespace
}  // namespace photon

namespace photon {
namespace {

// ---- Environments -------------------------------------------------------------------------------

TEST(SceneLoader, EnvironmentSkyAndDirectionalLights) {
    Scene uniform = load(sceneWith("lights", R"([{"type": "environment", "radiance": [1, 2, 3], "intensity": 2,
                                                   "rotate": [90, 0, 1, 0]}])"));
    ASSERT_NE(uniform.environmentLight, NONE);
    EXPECT_EQ(environmentScale(uniform.lights[uniform.environmentLight]), glm::vec3(2, 4, 6));
    EXPECT_NEAR(glm::length(environmentMapX(uniform.infiniteLights[0]) - glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
    Scene seen = load(sceneWith("lights", R"([{"type": "point", "position": [0, 3, 0], "power": 10},
                                              {"type": "environment", "radiance": [1, 1, 1], "lights": false}])"));
    EXPECT_EQ(seen.environmentLight, NONE);
    EXPECT_EQ(seen.lights.size(), 1u);
    Scene sky = load(sceneWith("lights", R"([{"type": "sky", "sun_direction": [0, 1, 1], "turbidity": 4,
                                             "resolution": [64, 32]}])"));
    EXPECT_EQ(sky.environment.map.width, 64u);
    EXPECT_EQ(sky.environment.source, "sky");
    EXPECT_EQ(sky.environmentTexels.size(), 64u * 32u);
    Scene sun = load(sceneWith("lights", R"([{"type": "directional", "direction": [0, -1, 0], "irradiance": 3}])"));
    EXPECT_EQ(sun.lights[0].type, LIGHT_DIRECTIONAL);
}

TEST(SceneLoader, EnvironmentMistakesNameTheKey) {
    EXPECT_NE(lightError(R"({"type": "environment", "radiance": [1, 1, 1]}, {"type": "sky"})").find("/lights/1: a second environment"),
              std::string::npos);
    EXPECT_NE(errorOf(sceneWith("lights", R"([{"type": "environment", "radiance": [1, 1, 1]}])").insert(1, R"("background": [1, 1, 1], )"))
                  .find("/background: the scene has an environment light too"),
              std::string::npos);
    EXPECT_NE(lightError(R"({"type": "environment"})").find("/lights/0: expected one of \"file\""), std::string::npos);
    EXPECT_NE(lightError(R"({"type": "environment", "radiance": [1, 1, 1], "file": "a.hdr"})").find("expected one of"),
              std::string::npos);
    EXPECT_NE(lightError(R"({"type": "environment", "file": "missing.hdr"})").find("/lights/0/file: missing.hdr"), std::string::npos);
    EXPECT_NE(lightError(R"({"type": "environment", "radiance": [-1, 1, 1]})").find("/lights/0/radiance"), std::string::npos);
    EXPECT_NE(lightError(R"({"type": "environment", "radiance": [1, 1, 1], "intensity": -1})").find("/lights/0/intensity"),
              std::string::npos);
    EXPECT_NE(lightError(R"({"type": "environment", "radiance": [1, 1, 1], "rotate": [90, 0, 0, 0]})").find("/lights/0/rotate"),
              std::string::npos);
    EXPECT_NE(lightError(R"({"type": "environment", "radiance": [0, 0, 0]})").find("nothing emits light"), std::string::npos);
    EXPECT_NE(lightError(R"({"type": "sky", "turbidity": 20})").find("/lights/0/turbidity"), std::string::npos);
    EXPECT_NE(lightError(R"({"type": "sky", "sun_direction": [0, 0, 0]})").find("/lights/0/sun_direction"), std::string::npos);
    EXPECT_NE(lightError(R"({"type": "sky", "resolution": [65536, 4]})").find("/lights/0/resolution/0"), std::string::npos);
    EXPECT_NE(lightError(R"({"type": "environment", "radiance": [1e38, 1e38, 1e38], "intensity": 1e30})").find("overflow"),
              std::string::npos);
}

}  // namespace
}  // namespace photon
