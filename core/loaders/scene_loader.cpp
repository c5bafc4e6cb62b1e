// Scene files: JSON text → Scene, built only through the Scene builder methods. Every value is read
// through a JsonNode, so that every check can say exactly where it failed.
#include "core/loaders/scene_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/loaders/environment_loader.h"
#include "core/loaders/json_node.h"
#include "core/loaders/model_loader.h"
#include "core/loaders/scene_media.h"
#include "core/scene/sky_model.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "core/system/input_file.h"
#include "embedded_scene.h"
#include "shared/constants.h"
#include "shared/math.h"

namespace photon {
namespace {

using nlohmann::json;
using Node = JsonNode;

// ---- Scene parts --------------------------------------------------------------------------------

CameraDesc readCamera(const Node& node) {
    node.allowKeys({"position", "look_at", "up", "fov", "lens_radius", "focus_distance"});
    CameraDesc camera;
    camera.position = node["position"].vec3();
    camera.lookAt = node["look_at"].vec3();
    glm::vec3 forward = camera.lookAt - camera.position;
    node["look_at"].checkNormalizable(forward, "must differ from position");
    if (node.has("up")) {
        camera.up = node["up"].direction();
    }
    // |forward × up| / |up| is the sine of their angle; below 1e-4 the image's roll is rounding noise.
    glm::vec3 right = glm::cross(glm::normalize(forward), glm::normalize(camera.up));
    if (glm::dot(right, right) < 1e-8f) {
        if (node.has("up")) {
            node["up"].fail("must not be parallel to look_at - position");
        }
        node.fail("the default up [0, 1, 0] is parallel to look_at - position: give \"up\"");
    }
    if (node.has("fov")) {
        camera.fovY = node["fov"].number({0.0, 180.0, true, true});
    }
    if (node.has("lens_radius")) {
        camera.lensRadius = node["lens_radius"].number(kNonNegative);
    }
    if (node.has("focus_distance")) {
        camera.focusDistance = node["focus_distance"].number(kNonNegative);
    }
    return camera;
}

// An Abbe number V_d (crown glass 59, diamond 55, polycarbonate 32, rutile 9.8) as the dispersion
// 20 / V_d of KHR_materials_dispersion (shared/dispersion.h); none without one. Below 1 no glass
// exists, and a tiny one would make the index infinite.
float readDispersion(const Node& node) {
    return node.has("abbe") ? float(20.0 / node["abbe"].number({1.0, 1e6, false, false})) : 0.0f;
}

Material readSurface(const Node& node) {
    const std::string& type = node["type"].string();
    if (type == "diffuse") {
        node.allowKeys({"type", "emission", "albedo"});
        return makeDiffuse(node["albedo"].rgb(kUnit));
    }
    if (type == "mirror") {
        node.allowKeys({"type", "emission", "reflectance"});
        return makeMirror(node.has("reflectance") ? node["reflectance"].rgb(kUnit) : glm::vec3(1.0f));
    }
    if (type == "glass") {
        node.allowKeys({"type", "emission", "ior", "tint", "abbe", "medium"});
        float ior = node.has("ior") ? node["ior"].number(kPositive) : 1.5f;
        Material m = makeGlass(ior, node.has("tint") ? node["tint"].rgb(kUnit) : glm::vec3(1.0f));
        m.dispersion = readDispersion(node);
        return m;
    }
    if (type == "glossy" || type == "reflective") {
        // Both are a Lambertian base plus a coat: a GGX lobe (glossy) or a perfect mirror (reflective).
        bool glossy = type == "glossy";
        const char* coat = glossy ? "specular" : "reflectance";
        if (glossy) {
            node.allowKeys({"type", "emission", "albedo", "specular", "roughness"});
        } else {
            node.allowKeys({"type", "emission", "albedo", "reflectance"});
        }
        glm::vec3 albedo = node["albedo"].rgb(kUnit);
        glm::vec3 specular = node[coat].rgb(kUnit);
        for (int c = 0; c < 3; ++c) {
            // The tolerance forgives decimal inputs such as 0.7 + 0.3 that round above 1 in float.
            if (albedo[c] + specular[c] > 1.0f + 1e-6f) {
                node.fail(std::string("albedo + ") + coat + " exceeds 1 in channel " + "rgb"[c] +
                          ": energy would be created");
            }
        }
        if (glossy) {
            return makeGlossy(albedo, specular, node["roughness"].number({0.001, 1.0, false, false}));
        }
        return makeReflective(albedo, specular);
    }
    if (type == "pbr") {
        // glTF's metallic-roughness model (shared/pbr.h), with transmission and a volume.
        node.allowKeys({"type", "emission", "base_color", "metallic", "roughness", "transmission", "ior", "thin_walled",
                        "attenuation_color", "attenuation_distance", "abbe", "medium"});
        Material m = makePbr(node["base_color"].rgb(kUnit), node.has("metallic") ? node["metallic"].number(kUnit) : 0.0f,
                             node.has("roughness") ? node["roughness"].number(kUnit) : 0.5f);
        if (node.has("transmission")) {
            m.transmission = node["transmission"].number(kUnit);
        }
        if (node.has("ior")) {
            m.ior = node["ior"].number({1.0, 10.0, false, false});
        }
        if (node.has("thin_walled") && node["thin_walled"].boolean()) {
            m.flags |= MATERIAL_FLAG_THIN_WALLED;
        }
        if (node.has("attenuation_color") != node.has("attenuation_distance")) {
            node.fail("attenuation_color and attenuation_distance come together");
        }
        if (node.has("attenuation_color")) {
            glm::vec3 colour = node["attenuation_color"].rgb({0.0, 1.0, true, false});
            float distance = node["attenuation_distance"].number(kPositive);
            m.attenuation = -glm::log(colour) / distance;  // Beer–Lambert: σ = −ln(colour)/distance
        }
        m.dispersion = readDispersion(node);
        return m;
    }
    node["type"].fail("unknown material type '" + type + "' (expected diffuse|mirror|glass|glossy|reflective|pbr)");
}

// Any material may also emit (radiance from its front): triangles and meshes of an emitting
// material become an area light (Scene::finalize).
Material readMaterial(const Node& node) {
    Material m = readSurface(node);
    if (node.has("emission")) {
        m.emission = node["emission"].rgb(kNonNegative);
    }
    return m;
}

void readMaterials(Scene& scene, const Node& node, const MediaByName& media) {
    for (const auto& [name, material] : node.members()) {
        bool reserved = name.compare(0, 5, "light") == 0 && name.size() > 5 &&
                        std::isdigit(static_cast<unsigned char>(name[5]));
        if (reserved) {
            material.fail("names starting with 'light' and a digit are reserved for the emitters of area lights");
        }
        Material m = readMaterial(material);
        if (material.has("medium")) {
            // Inside a closed object of this material (shared/medium.h); its absorption there.
            if (m.attenuation != glm::vec3(0.0f)) {
                material["medium"].fail("the material has attenuation_color too: give the absorption in the medium");
            }
            m.medium = readMaterialMedium(scene, material["medium"], media);
        }
        scene.addMaterial(name, m);
    }
}

std::uint32_t materialOf(const Scene& scene, const Node& object) {
    Node ref = object["material"];
    std::uint32_t material = scene.findMaterial(ref.string());
    if (material == NONE) {
        ref.fail("unknown material " + quote(ref.string()));
    }
    return material;
}

// Spheres, planes, quads and boxes do not emit: area lights of those shapes are lights.
std::uint32_t nonEmittingMaterialOf(const Scene& scene, const Node& object) {
    std::uint32_t material = materialOf(scene, object);
    if (!isBlack(scene.materials[material].emission)) {
        object["material"].fail(quote(object["material"].string()) + " emits, and only triangles and meshes emit " +
                                "(a sphere or quad that shines is a light: see \"lights\")");
    }
    return material;
}

// A mesh object's "transform": scale (a number or a vec3), then rotate [degrees, axis], then
// translate; or a row-major 4×4 "matrix".
glm::mat4 readTransform(const Node& node) {
    node.allowKeys({"scale", "rotate", "translate", "matrix"});
    if (node.has("matrix")) {
        if (node.has("scale") || node.has("rotate") || node.has("translate")) {
            node["matrix"].fail("a matrix replaces scale, rotate and translate: give one or the others");
        }
        std::vector<Node> values = node["matrix"].elements();
        if (values.size() != 16) {
            node["matrix"].fail("expected 16 numbers, row by row");
        }
        glm::mat4 m;
        for (int row = 0; row < 4; ++row) {
            for (int column = 0; column < 4; ++column) {
                m[column][row] = values[std::size_t(4 * row + column)].number();
            }
        }
        if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f) {
            node["matrix"].fail("the last row must be [0, 0, 0, 1] (an affine transform)");
        }
        float det = glm::determinant(glm::mat3(m));
        if (!(std::abs(det) > 1e-30f) || !std::isfinite(det)) {
            node["matrix"].fail("not invertible (its 3x3 part has determinant " + formatNumber(det) + ")");
        }
        return m;
    }
    glm::vec3 scale(1.0f);
    if (node.has("scale")) {
        Node n = node["scale"];
        scale = n.isNumber() ? glm::vec3(n.number()) : n.triple("expected a number or an array of 3 numbers", kFinite);
        if (scale.x == 0.0f || scale.y == 0.0f || scale.z == 0.0f) {
            n.fail("must not be zero on any axis");
        }
    }
    float degrees = 0.0f;
    glm::vec3 axis(0.0f, 1.0f, 0.0f);
    if (node.has("rotate")) {
        Node r = node["rotate"];
        std::vector<Node> v = r.elements();
        if (v.size() != 4) {
            r.fail("expected [degrees, axis x, axis y, axis z]");
        }
        degrees = v[0].number();
        axis = glm::vec3(v[1].number(), v[2].number(), v[3].number());
        r.checkNormalizable(axis, "the axis must be non-zero");
    }
    glm::vec3 translate = node.has("translate") ? node["translate"].vec3() : glm::vec3(0.0f);
    return composeTransform(scale, degrees, axis, translate);
}

// A model file as an object: its path relative to the scene file, its file's materials or one of
// the scene's, and a transform.
void readMesh(Scene& scene, const Node& node, const std::string& folder, const FileReader& read, const PathPolicy& paths) {
    node.allowKeys({"type", "file", "material", "transform"});
    ModelOptions options;
    options.paths = paths;
    if (node.has("material")) {
        options.material = materialOf(scene, node);
    }
    if (node.has("transform")) {
        options.transform = readTransform(node["transform"]);
    }
    Node file = node["file"];
    const std::string& name = file.string();
    if (name.empty()) {
        file.fail("must not be empty");
    }
    if (!isModelFile(name)) {
        file.fail(quote(name) + " is not a model file Photon reads (.obj, .gltf, .glb)");
    }
    std::string path = !name.empty() && name[0] == '/' ? name : folder + name;
    std::uint64_t dropped = scene.droppedTriangles;
    try {
        addModel(scene, path, read(path, "model file"), options, read);
    } catch (const InputError& e) {
        file.fail(e.what());
    }
    if (scene.droppedTriangles > dropped) {
        scene.warnings.push_back(path + " (" + file.where() + "): " + droppedMessage(scene.droppedTriangles - dropped));
    }
}

void readObject(Scene& scene, const Node& node, const std::string& folder, const FileReader& read, const PathPolicy& paths) {
    const std::string& type = node["type"].string();
    if (type == "sphere") {
        node.allowKeys({"type", "material", "center", "radius"});
        std::uint32_t material = nonEmittingMaterialOf(scene, node);
        glm::vec3 center = node["center"].vec3();
        scene.addSphere(center, node["radius"].number(kPositive), material);
    } else if (type == "plane") {
        node.allowKeys({"type", "material", "point", "normal"});
        std::uint32_t material = nonEmittingMaterialOf(scene, node);
        glm::vec3 point = node["point"].vec3();
        scene.addPlane(point, node["normal"].direction(), material);
    } else if (type == "quad") {
        node.allowKeys({"type", "material", "corner", "edge_u", "edge_v"});
        std::uint32_t material = nonEmittingMaterialOf(scene, node);
        glm::vec3 corner = node["corner"].vec3();
        glm::vec3 edgeU = node["edge_u"].vec3();
        glm::vec3 edgeV = node["edge_v"].vec3();
        node.checkSpan(edgeU, edgeV, "edge_u and edge_v are parallel or zero (area at most 1e-12)");
        scene.addQuad(corner, edgeU, edgeV, material);
    } else if (type == "triangle") {
        node.allowKeys({"type", "material", "vertices"});
        std::uint32_t material = materialOf(scene, node);
        Node vertices = node["vertices"];
        std::vector<Node> v = vertices.elements();
        if (v.size() != 3) {
            vertices.fail("expected an array of 3 vertices");
        }
        glm::vec3 a = v[0].vec3();
        glm::vec3 b = v[1].vec3();
        glm::vec3 c = v[2].vec3();
        vertices.checkSpan(b - a, c - a, "degenerate triangle: the vertices are collinear or coincide");
        scene.addTriangle(a, b, c, material);
    } else if (type == "mesh") {
        readMesh(scene, node, folder, read, paths);
    } else if (type == "box") {
        node.allowKeys({"type", "material", "min", "max"});
        std::uint32_t material = nonEmittingMaterialOf(scene, node);
        glm::vec3 lo = node["min"].vec3();
        glm::vec3 hi = node["max"].vec3();
        if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) {
            node["max"].fail("must be greater than min on every axis");
        }
        // Faces with outward normals: for the axis a, the edges along a+1 and a+2 span +a.
        glm::vec3 size = hi - lo;
        for (int a = 0; a < 3; ++a) {
            glm::vec3 edge1(0.0f), edge2(0.0f);
            edge1[(a + 1) % 3] = size[(a + 1) % 3];
            edge2[(a + 2) % 3] = size[(a + 2) % 3];
            node.checkSpan(edge1, edge2, "too thin: a face has an area of at most 1e-12");
            glm::vec3 far = lo;
            far[a] = hi[a];
            scene.addQuad(lo, edge2, edge1, material);
            scene.addQuad(far, edge1, edge2, material);
        }
    } else {
        node["type"].fail("unknown object type " + quote(type) + " (expected sphere|plane|quad|triangle|box|mesh)");
    }
}

// Flux per channel: an RGB array or one number for all three; non-negative, not all zero.
glm::vec3 readPower(const Node& node) {
    glm::vec3 power = node.isNumber() ? glm::vec3(node.number(kNonNegative))
                                      : node.triple("expected an RGB array of 3 numbers or a number", kNonNegative);
    if (power == glm::vec3(0.0f)) {
        node.fail("must be positive in at least one channel");
    }
    return power;
}

// A rotation "rotate": [degrees, axis x, axis y, axis z].
glm::mat3 readRotation(const Node& r) {
    std::vector<Node> v = r.elements();
    if (v.size() != 4) {
        r.fail("expected [degrees, axis x, axis y, axis z]");
    }
    glm::vec3 axis(v[1].number(), v[2].number(), v[3].number());
    r.checkNormalizable(axis, "the axis must be non-zero");
    return environmentRotation(v[0].number(), axis);
}

// The environment: one radiance, or a map file (.hdr, .exr) relative to the scene file; scaled
// by "intensity", turned by "rotate"; it lights the scene unless "lights" is false.
// What every environment has: its intensity, its rotation, whether it lights the scene.
void readEnvironmentCommon(const Node& node, EnvironmentLight& env, glm::vec3 radiance) {
    float intensity = node.has("intensity") ? node["intensity"].number(kNonNegative) : 1.0f;
    env.radiance = radiance * intensity;
    if (node.has("rotate")) {
        env.rotation = readRotation(node["rotate"]);
    }
    env.lights = node.has("lights") ? node["lights"].boolean() : true;
}

void readEnvironment(Scene& scene, const Node& node, const std::string& folder, const FileReader& read) {
    node.allowKeys({"type", "file", "radiance", "intensity", "rotate", "lights"});
    if (node.has("file") == node.has("radiance")) {
        node.fail("expected one of \"file\" (an .hdr or .exr map) and \"radiance\"");
    }
    EnvironmentLight env;
    if (node.has("radiance")) {
        readEnvironmentCommon(node, env, node["radiance"].rgb(kNonNegative));
    } else {
        Node file = node["file"];
        const std::string& name = file.string();
        if (name.empty()) {
            file.fail("must not be empty");
        }
        std::string path = name[0] == '/' ? name : folder + name;
        try {
            env.map = decodeEnvironmentMap(read(path, "environment map"), path);
        } catch (const InputError& e) {
            file.fail(e.what());
        }
        env.source = name;
        readEnvironmentCommon(node, env, glm::vec3(1.0f));
    }
    scene.setEnvironment(std::move(env));
}

// The daylight sky of core/scene/sky_model.h, as an environment map.
void readSky(Scene& scene, const Node& node) {
    node.allowKeys({"type", "sun_direction", "turbidity", "ground_albedo", "resolution", "intensity", "rotate", "lights"});
    SkyDesc sky;
    if (node.has("sun_direction")) {
        sky.sunDirection = node["sun_direction"].direction();
    }
    if (node.has("turbidity")) {
        sky.turbidity = node["turbidity"].number({1.7, 10.0, false, false});
    }
    if (node.has("ground_albedo")) {
        sky.groundAlbedo = node["ground_albedo"].number({0.0, 1.0, false, false});
    }
    if (node.has("resolution")) {
        Node r = node["resolution"];
        std::vector<Node> v = r.elements();
        if (v.size() != 2) {
            r.fail("expected [width, height]");
        }
        sky.width = v[0].integer(1, kEnvironmentWidthMax);
        sky.height = v[1].integer(1, kEnvironmentHeightMax);
    }
    EnvironmentLight env;
    env.source = "sky";
    env.map = makeSkyMap(sky);
    readEnvironmentCommon(node, env, glm::vec3(1.0f));
    scene.setEnvironment(std::move(env));
}

void readLight(Scene& scene, const Node& node, const std::string& folder, const FileReader& read) {
    const std::string& type = node["type"].string();
    if (type == "environment") {
        readEnvironment(scene, node, folder, read);
    } else if (type == "sky") {
        readSky(scene, node);
    } else if (type == "directional") {
        node.allowKeys({"type", "direction", "irradiance"});
        glm::vec3 direction = node["direction"].direction();
        scene.addDirectionalLight(direction, readPower(node["irradiance"]));
    } else if (type == "point") {
        node.allowKeys({"type", "power", "position", "emission", "direction"});
        glm::vec3 position = node["position"].vec3();
        std::string emission = node.has("emission") ? node["emission"].string() : "isotropic";
        if (emission == "isotropic") {
            if (node.has("direction")) {
                node["direction"].fail("only for hemisphere emission");
            }
            scene.addPointLight(position, readPower(node["power"]));
        } else if (emission == "hemisphere") {
            glm::vec3 axis = node["direction"].direction();
            scene.addHemisphereLight(position, axis, readPower(node["power"]));
        } else {
            node["emission"].fail("unknown emission " + quote(emission) + " (expected isotropic|hemisphere)");
        }
    } else if (type == "spot") {
        node.allowKeys({"type", "power", "position", "direction", "angle", "falloff_start"});
        glm::vec3 position = node["position"].vec3();
        glm::vec3 direction = node["direction"].direction();
        float angle = node["angle"].number({0.0, 90.0, true, false});
        float falloffStart =
            node.has("falloff_start") ? node["falloff_start"].number({0.0, angle, false, false}) : angle;
        scene.addSpotLight(position, direction, readPower(node["power"]), angle, falloffStart);
        // The cone is kept as 1 - cos(angle), which a float cannot hold below about 1e-17 degrees.
        if (scene.lights.back().spotOuter == 0.0f) {
            node["angle"].fail("too small: 1 - cos(angle) underflows a float");
        }
    } else if (type == "sphere") {
        node.allowKeys({"type", "power", "center", "radius"});
        glm::vec3 center = node["center"].vec3();
        float radius = node["radius"].number(kPositive);
        float area = 4.0f * PI * radius * radius;  // the emitted radiance is Φ / (π · area)
        if (!(area > 1e-12f && std::isfinite(area))) {
            node["radius"].fail("out of range: the area 4 pi r^2 must be above 1e-12 and finite as a float");
        }
        scene.addSphereLight(center, radius, readPower(node["power"]));
    } else if (type == "quad") {
        node.allowKeys({"type", "power", "corner", "edge_u", "edge_v"});
        glm::vec3 corner = node["corner"].vec3();
        glm::vec3 edgeU = node["edge_u"].vec3();
        glm::vec3 edgeV = node["edge_v"].vec3();
        node.checkSpan(edgeU, edgeV, "edge_u and edge_v are parallel or zero (area at most 1e-12)");
        scene.addQuadLight(corner, edgeU, edgeV, readPower(node["power"]));
    } else {
        node["type"].fail("unknown light type " + quote(type) + " (expected point|spot|sphere|quad|directional|environment|sky)");
    }
}

// Whether one of the lights was the environment.
bool readLights(Scene& scene, const Node& node, const std::string& folder, const FileReader& read) {
    std::vector<Node> lights = node.elements();
    if (lights.empty()) {
        node.fail("the scene has no lights");
    }
    if (lights.size() > LIGHTS_MAX) {
        node.fail("too many lights: " + std::to_string(lights.size()) + " (at most " + std::to_string(LIGHTS_MAX) +
                  ")");
    }
    const Node* environment = nullptr;
    for (const Node& light : lights) {
        const std::string& type = light["type"].string();
        if (type == "environment" || type == "sky") {
            if (environment != nullptr) {
                light.fail("a second environment: a scene has at most one (the first is " + environment->where() + ")");
            }
            environment = &light;
        }
        readLight(scene, light, folder, read);
    }
    return environment != nullptr;
}

// The render block: each key a setting of core/settings/setting_specs.h, checked there.
void readRender(const Node& node, RenderSettings& s) {
    for (const auto& [key, value] : node.members()) {
        const SettingSpec* spec = findSetting(key);
        if (spec == nullptr || key != spec->key) {
            value.fail("unknown key");
        }
        try {
            const json& v = value.value();
            if (v.is_number()) {
                setSettingNumber(s, *spec, v.get<double>(), v.dump(), value.where());
            } else if (v.is_string() && spec->kind == SettingKind::Choice) {
                setSetting(s, *spec, v.get<std::string>(), value.where());
            } else if (v.is_boolean() && spec->kind == SettingKind::Flag) {
                setSetting(s, *spec, v.get<bool>() ? "true" : "false", value.where());  // given, as any other
            } else {
                const char* expected = spec->kind == SettingKind::Choice ? "a string"
                                       : spec->kind == SettingKind::Flag ? "true or false"
                                       : spec->kind == SettingKind::Integer ? "an integer"
                                                                            : "a number";
                value.fail(std::string("expected ") + expected + " (got " + v.type_name() + ")");
            }
        } catch (const InputError& e) {
            throw InputError(printable(e.what()));
        }
    }
}

}  // namespace

Scene loadSceneJson(const std::string& text, const std::string& sourceName, const std::string& folder,
                    const FileReader& read, const PathPolicy& paths) {
    const json document = parseJson(text, sourceName);
    const Node root(document, "", sourceName);
    root.allowKeys({"name", "camera", "background", "media", "medium", "materials", "objects", "lights", "render"});

    Scene scene;
    if (root.has("name")) {
        scene.name = root["name"].string();
    }
    scene.camera = readCamera(root["camera"]);
    if (root.has("background")) {
        scene.setBackground(root["background"].rgb(kNonNegative));
    }
    MediaByName media = root.has("media") ? readMedia(scene, root["media"], MediaFiles{folder, read}) : MediaByName{};
    readMaterials(scene, root["materials"], media);
    if (root.has("medium")) {
        readSceneMedium(scene, root["medium"], media);
    }
    for (const Node& object : root["objects"].elements()) {
        readObject(scene, object, folder, read, paths);
    }
    if (readLights(scene, root["lights"], folder, read) && root.has("background")) {
        root["background"].fail("the scene has an environment light too: give its radiance there, with \"lights\": false");
    }
    // Area lights have added their surfaces by now.
    if (scene.spheres.empty() && scene.planes.empty() && scene.quads.empty() && scene.triangles.empty()) {
        root["objects"].fail("the scene has no geometry: nothing for light to fall on or the camera to see");
    }
    if (root.has("render")) {
        readRender(root["render"], scene.render);
    }
    scene.finalize();
    if (scene.lights.empty()) {
        root["lights"].fail("nothing emits light: the only light is an environment that is black or does not light");
    }
    for (const Light& l : scene.lights) {
        if (!std::isfinite(l.power.x) || !std::isfinite(l.power.y) || !std::isfinite(l.power.z)) {
            root["lights"].fail(std::string("the ") + lightTypeName(l.type) +
                                " light's power overflows a float (too bright for the scene's size)");
        }
    }
    return scene;
}

Scene loadSceneFile(const std::string& path, const PathPolicy& paths) {
    if (isModelFile(path)) {
        return loadModelScene(path, paths);
    }
    return loadSceneJson(readInputFile(path, kSceneFileLimit, "scene file"), path, folderOf(path), defaultFileReader(), paths);
}

Scene defaultScene() { return loadSceneJson(kEmbeddedCornellJson, "<embedded cornell.json>", "", defaultFileReader()); }

}  // namespace photon
