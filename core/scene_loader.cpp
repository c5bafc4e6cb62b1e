// Scene files: JSON text → Scene, built only through the Scene builder methods. A Node carries a
// JSON value together with its JSON pointer, so that every check can say exactly where it failed.
#include "scene_loader.h"

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

#include "embedded_scene.h"
#include "error.h"
#include "shared/constants.h"

namespace photon {
namespace {

using nlohmann::json;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Control characters escaped, so that a message stays on one line whatever the input holds.
std::string printable(const std::string& s) {
    std::string out;
    for (char c : s) {
        auto u = static_cast<unsigned char>(c);
        if (u < 0x20 || u == 0x7f) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\x%02x", u);
            out += escaped;
        } else {
            out += c;
        }
    }
    return out;
}

std::string format(double x) {
    std::ostringstream out;
    out << x;
    return out.str();
}

// One reference token of a JSON pointer (RFC 6901): '~' → "~0", '/' → "~1".
std::string pointerToken(const std::string& key) {
    std::string out;
    for (char c : key) {
        out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
    }
    return out;
}

// The values a setting accepts, for range checks and their messages.
struct Interval {
    double lo, hi;
    bool openLo, openHi;

    bool contains(double x) const { return (openLo ? x > lo : x >= lo) && (openHi ? x < hi : x <= hi); }

    std::string describe() const {
        if (lo == 0.0 && hi == kInfinity) {
            return openLo ? "positive" : "non-negative";
        }
        return std::string("in ") + (openLo ? "(" : "[") + format(lo) + ", " + format(hi) + (openHi ? ")" : "]");
    }
};

constexpr Interval kFinite{-kInfinity, kInfinity, true, true};
constexpr Interval kPositive{0.0, kInfinity, true, true};
constexpr Interval kNonNegative{0.0, kInfinity, false, true};
constexpr Interval kUnit{0.0, 1.0, false, false};

// A JSON value and where it is. Every accessor checks the type first, so nlohmann never throws here.
class Node {
public:
    Node(const json& value, std::string pointer, const std::string& source)
        : value_(value), pointer_(std::move(pointer)), source_(source) {}

    [[noreturn]] void fail(const std::string& reason) const {
        throw InputError(printable(source_ + ": " + (pointer_.empty() ? "/" : pointer_) + ": " + reason));
    }

    // ---- Objects -------------------------------------------------------------------------------

    // Requires an object whose keys are all among `allowed`.
    void allowKeys(std::initializer_list<const char*> allowed) const {
        expectObject();
        for (const auto& member : value_.items()) {
            if (std::none_of(allowed.begin(), allowed.end(), [&](const char* k) { return member.key() == k; })) {
                child(member.key()).fail("unknown key");
            }
        }
    }

    bool has(const char* key) const { return value_.is_object() && value_.contains(key); }

    // A required key.
    Node operator[](const char* key) const {
        expectObject();
        if (!value_.contains(key)) {
            fail(std::string("missing required key '") + key + "'");
        }
        return child(key);
    }

    std::vector<std::pair<std::string, Node>> members() const {
        expectObject();
        std::vector<std::pair<std::string, Node>> out;
        for (const auto& member : value_.items()) {
            out.emplace_back(member.key(), child(member.key()));
        }
        return out;
    }

    // ---- Arrays --------------------------------------------------------------------------------

    std::vector<Node> elements() const {
        if (!value_.is_array()) {
            fail(expected("an array"));
        }
        std::vector<Node> out;
        for (std::size_t i = 0; i < value_.size(); ++i) {
            out.push_back(element(i));
        }
        return out;
    }

    // ---- Values --------------------------------------------------------------------------------

    bool isNumber() const { return value_.is_number(); }

    // A number, as the float the renderer will see, checked against `range`.
    float number(const Interval& range = kFinite) const {
        if (!value_.is_number()) {
            fail(expected("a number"));
        }
        double x = value_.get<double>();
        if (!(std::abs(x) <= std::numeric_limits<float>::max())) {
            fail("must be a finite number within the range of a float (got " + value_.dump() + ")");
        }
        auto f = static_cast<float>(x);
        if (!range.contains(f)) {
            fail("must be " + range.describe() + " (got " + value_.dump() + ")");
        }
        return f;
    }

    // An integral number in [lo, hi]; 16 and 16.0 are both integral.
    std::uint32_t integer(std::uint32_t lo, std::uint32_t hi) const {
        if (!value_.is_number()) {
            fail(expected("an integer"));
        }
        double x = value_.get<double>();
        if (!(x >= lo && x <= hi && x == std::floor(x))) {
            fail("must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                 value_.dump() + ")");
        }
        return static_cast<std::uint32_t>(x);
    }

    const std::string& string() const {
        if (!value_.is_string()) {
            fail(expected("a string"));
        }
        return value_.get_ref<const std::string&>();
    }

    // One of the names of a settings enum (settings.h).
    template <typename E>
    E setting() const {
        E out{};
        if (!parse(string(), out)) {
            fail("unknown value '" + string() + "' (expected " + choices(out) + ")");
        }
        return out;
    }

    glm::vec3 vec3() const { return triple("expected an array of 3 numbers", kFinite); }

    glm::vec3 rgb(const Interval& range) const { return triple("expected an RGB array of 3 numbers", range); }

    // An array of 3 numbers, each checked against `range`; `mismatch` is the message for anything else.
    glm::vec3 triple(const char* mismatch, const Interval& range) const {
        if (!value_.is_array() || value_.size() != 3) {
            fail(mismatch);
        }
        return {element(0).number(range), element(1).number(range), element(2).number(range)};
    }

    // A vector the renderer normalises.
    glm::vec3 direction() const {
        glm::vec3 v = vec3();
        checkNormalizable(v, "must be non-zero");
        return v;
    }

    // Fails unless |v|² is a positive, finite float: `ifZero` says why a zero vector is wrong here.
    void checkNormalizable(glm::vec3 v, const std::string& ifZero) const {
        float length2 = glm::dot(v, v);
        if (length2 == 0.0f) {
            fail(ifZero);
        }
        if (!std::isfinite(length2)) {
            fail("too large: the squared length overflows a float");
        }
    }

    // Fails unless the parallelogram spanned by u and v has an area above 1e-12 whose square (which
    // intersection divides by) is a finite float; `ifDegenerate` is the message for a flat one.
    void checkSpan(glm::vec3 u, glm::vec3 v, const std::string& ifDegenerate) const {
        glm::vec3 n = glm::cross(u, v);
        float area2 = glm::dot(n, n);
        if (!std::isfinite(area2)) {
            fail("too large: the area overflows a float");
        }
        if (!(std::sqrt(area2) > 1e-12f)) {
            fail(ifDegenerate);
        }
    }

private:
    void expectObject() const {
        if (!value_.is_object()) {
            fail(expected("an object"));
        }
    }

    std::string expected(const char* what) const {
        return std::string("expected ") + what + " (got " + value_.type_name() + ")";
    }

    Node child(const std::string& key) const {
        return Node(value_.find(key).value(), pointer_ + "/" + pointerToken(key), source_);
    }

    Node element(std::size_t i) const { return Node(value_[i], pointer_ + "/" + std::to_string(i), source_); }

    const json& value_;
    std::string pointer_;
    const std::string& source_;
};

// ---- JSON syntax --------------------------------------------------------------------------------

// A SAX consumer that only records the first syntax error: where it is and what nlohmann says.
struct SyntaxErrorLocator : nlohmann::json_sax<json> {
    std::size_t byte = 0;  // 1-based index of the last character read; size + 1 at the end of input
    std::string message;

    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override { return true; }
    bool key(string_t&) override { return true; }
    bool end_object() override { return true; }
    bool start_array(std::size_t) override { return true; }
    bool end_array() override { return true; }
    bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) override {
        byte = position;
        message = e.what();
        return false;
    }
};

// nlohmann's message without its decorations: "[json.exception.parse_error.101] parse error at line
// 1, column 8: syntax error while parsing value - invalid literal; last read: 'N'" → "invalid
// literal; last read: 'N'".
std::string essentialPart(std::string message) {
    auto dropThrough = [&](const std::string& prefix, const std::string& separator) {
        if (message.compare(0, prefix.size(), prefix) == 0) {
            std::size_t end = message.find(separator);
            if (end != std::string::npos) {
                message.erase(0, end + separator.size());
            }
        }
    };
    dropThrough("[json.exception.", "] ");
    dropThrough("parse error", ": ");
    dropThrough("syntax error while parsing ", " - ");
    return message;
}

json parseJson(const std::string& text, const std::string& source) {
    json document = json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (!document.is_discarded()) {
        return document;
    }
    // Parse again to find out where and why: the exception-free parse above only says that it failed.
    SyntaxErrorLocator locator;
    json::sax_parse(text, &locator);
    // The offending character (0-based) and its line and column (1-based).
    std::size_t offset = std::min(locator.byte > 0 ? locator.byte - 1 : 0, text.size());
    std::size_t line = 1;
    std::size_t column = 1;
    for (std::size_t i = 0; i < offset; ++i) {
        column = text[i] == '\n' ? 1 : column + 1;
        line += text[i] == '\n' ? 1 : 0;
    }
    throw InputError(printable(source + ": line " + std::to_string(line) + ", column " +
                               std::to_string(column) + ": " + essentialPart(locator.message)));
}

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

Material readMaterial(const Node& node) {
    const std::string& type = node["type"].string();
    if (type == "diffuse") {
        node.allowKeys({"type", "albedo"});
        return makeDiffuse(node["albedo"].rgb(kUnit));
    }
    if (type == "mirror") {
        node.allowKeys({"type", "reflectance"});
        return makeMirror(node.has("reflectance") ? node["reflectance"].rgb(kUnit) : glm::vec3(1.0f));
    }
    if (type == "glass") {
        node.allowKeys({"type", "ior", "tint"});
        float ior = node.has("ior") ? node["ior"].number(kPositive) : 1.5f;
        return makeGlass(ior, node.has("tint") ? node["tint"].rgb(kUnit) : glm::vec3(1.0f));
    }
    if (type == "glossy" || type == "reflective") {
        // Both are a Lambertian base plus a coat: a GGX lobe (glossy) or a perfect mirror (reflective).
        bool glossy = type == "glossy";
        const char* coat = glossy ? "specular" : "reflectance";
        if (glossy) {
            node.allowKeys({"type", "albedo", "specular", "roughness"});
        } else {
            node.allowKeys({"type", "albedo", "reflectance"});
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
    node["type"].fail("unknown material type '" + type + "' (expected diffuse|mirror|glass|glossy|reflective)");
}

void readMaterials(Scene& scene, const Node& node) {
    for (const auto& [name, material] : node.members()) {
        bool reserved = name.compare(0, 5, "light") == 0 && name.size() > 5 &&
                        std::isdigit(static_cast<unsigned char>(name[5]));
        if (reserved) {
            material.fail("names starting with 'light' and a digit are reserved for the emitters of area lights");
        }
        scene.addMaterial(name, readMaterial(material));
    }
}

std::uint32_t materialOf(const Scene& scene, const Node& object) {
    Node ref = object["material"];
    std::uint32_t material = scene.findMaterial(ref.string());
    if (material == NONE) {
        ref.fail("unknown material '" + ref.string() + "'");
    }
    return material;
}

void readObject(Scene& scene, const Node& node) {
    const std::string& type = node["type"].string();
    if (type == "sphere") {
        node.allowKeys({"type", "material", "center", "radius"});
        std::uint32_t material = materialOf(scene, node);
        glm::vec3 center = node["center"].vec3();
        scene.addSphere(center, node["radius"].number(kPositive), material);
    } else if (type == "plane") {
        node.allowKeys({"type", "material", "point", "normal"});
        std::uint32_t material = materialOf(scene, node);
        glm::vec3 point = node["point"].vec3();
        scene.addPlane(point, node["normal"].direction(), material);
    } else if (type == "quad") {
        node.allowKeys({"type", "material", "corner", "edge_u", "edge_v"});
        std::uint32_t material = materialOf(scene, node);
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
    } else if (type == "box") {
        node.allowKeys({"type", "material", "min", "max"});
        std::uint32_t material = materialOf(scene, node);
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
        node["type"].fail("unknown object type '" + type + "' (expected sphere|plane|quad|triangle|box)");
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

void readLight(Scene& scene, const Node& node) {
    const std::string& type = node["type"].string();
    if (type == "point") {
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
            node["emission"].fail("unknown emission '" + emission + "' (expected isotropic|hemisphere)");
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
        node["type"].fail("unknown light type '" + type + "' (expected point|spot|sphere|quad)");
    }
}

void readLights(Scene& scene, const Node& node) {
    std::vector<Node> lights = node.elements();
    if (lights.empty()) {
        node.fail("the scene has no lights");
    }
    if (lights.size() > LIGHTS_MAX) {
        node.fail("too many lights: " + std::to_string(lights.size()) + " (at most " + std::to_string(LIGHTS_MAX) +
                  ")");
    }
    for (const Node& light : lights) {
        readLight(scene, light);
    }
}

void readRender(const Node& node, RenderSettings& s) {
    node.allowKeys({"width", "height", "photons", "frames", "caustic_fraction", "estimator", "kernel", "radius",
                    "caustic_radius", "k", "alpha", "global", "gather_rays", "light_samples", "max_eye_depth",
                    "max_photon_depth", "grid", "grid_resolution", "cell_size", "gather_budget", "photon_capacity", "seed",
                    "exposure", "tonemap"});
    if (node.has("width")) s.width = node["width"].integer(1, 16384);
    if (node.has("height")) s.height = node["height"].integer(1, 16384);
    if (node.has("photons")) s.photons = node["photons"].integer(1, 1u << 28);
    if (node.has("frames")) s.frames = node["frames"].integer(1, 1000000);
    if (node.has("caustic_fraction")) s.causticFraction = node["caustic_fraction"].number({0.0, 1.0, false, true});
    if (node.has("estimator")) s.estimator = node["estimator"].setting<Estimator>();
    if (node.has("kernel")) s.kernel = node["kernel"].setting<Kernel>();
    if (node.has("radius")) s.radius = node["radius"].number(kPositive);
    if (node.has("caustic_radius")) s.causticRadius = node["caustic_radius"].number(kPositive);
    if (node.has("k")) s.k = node["k"].integer(1, KNN_MAX);
    if (node.has("alpha")) s.alpha = node["alpha"].number({0.0, 1.0, true, true});
    if (node.has("global")) s.globalMode = node["global"].setting<GlobalMode>();
    if (node.has("gather_rays")) s.gatherRays = node["gather_rays"].integer(1, 1024);
    if (node.has("light_samples")) s.lightSamples = node["light_samples"].integer(1, 1024);
    if (node.has("max_eye_depth")) s.maxEyeDepth = node["max_eye_depth"].integer(1, 64);
    if (node.has("max_photon_depth")) s.maxPhotonDepth = node["max_photon_depth"].integer(1, 64);
    if (node.has("grid")) s.grid = node["grid"].setting<GridKind>();
    if (node.has("grid_resolution")) s.gridResolution = node["grid_resolution"].integer(1, 1024);
    if (node.has("cell_size")) s.cellSize = node["cell_size"].number({1.0, 64.0, false, false});
    if (node.has("gather_budget")) s.gatherBudget = node["gather_budget"].integer(0, 1u << 30);
    if (node.has("photon_capacity")) s.photonCapacity = node["photon_capacity"].number({1.0, 64.0, false, false});
    if (node.has("seed")) s.seed = node["seed"].integer(0, std::numeric_limits<std::uint32_t>::max());
    if (node.has("exposure")) s.exposure = node["exposure"].number();
    if (node.has("tonemap")) s.tonemap = node["tonemap"].setting<Tonemap>();
}

}  // namespace

Scene loadSceneJson(const std::string& text, const std::string& sourceName) {
    const json document = parseJson(text, sourceName);
    const Node root(document, "", sourceName);
    root.allowKeys({"name", "camera", "background", "materials", "objects", "lights", "render"});

    Scene scene;
    if (root.has("name")) {
        scene.name = root["name"].string();
    }
    scene.camera = readCamera(root["camera"]);
    if (root.has("background")) {
        scene.background = root["background"].rgb(kNonNegative);
    }
    readMaterials(scene, root["materials"]);
    for (const Node& object : root["objects"].elements()) {
        readObject(scene, object);
    }
    readLights(scene, root["lights"]);
    if (root.has("render")) {
        readRender(root["render"], scene.render);
    }
    scene.finalize();
    return scene;
}

Scene loadSceneFile(const std::string& path) {
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
        throw InputError(printable(path + ": is a directory, not a scene file"));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw InputError(printable(path + ": cannot open file"));
    }
    std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    return loadSceneJson(text, path);
}

Scene defaultScene() { return loadSceneJson(kEmbeddedCornellJson, "<embedded cornell.json>"); }

}  // namespace photon
