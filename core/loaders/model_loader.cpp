#include "core/loaders/model_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "core/scene/studio_environment.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "core/system/input_file.h"

namespace photon {
namespace {

// The lights of a model without its own (W/m² of the sun; the studio map's scale).
constexpr double kStudioSunIrradiance = 3.0;
constexpr double kStudioRadiance = 1.0;

std::string lowerExtension(const std::string& path) {
    std::size_t dot = path.find_last_of('.');
    std::size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) {
        return "";
    }
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace

std::string droppedMessage(std::uint64_t count) {
    return std::to_string(count) + (count == 1 ? " triangle" : " triangles") + " without area (or not finite) dropped";
}

std::string folderOf(const std::string& path) {
    std::size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

std::string namedFile(const std::string& folder, const std::string& name) {
    std::string file = name;
    std::replace(file.begin(), file.end(), '\\', '/');
    if (file.empty() || file[0] != '/') {
        file = folder + file;
    }
    return std::filesystem::path(file).lexically_normal().generic_string();
}

namespace {

// Whether `file` lies in `folder`'s tree once both are absolute with every symbolic link
// followed: a comparison of path components, so that /models/a is not taken to be inside
// /models/ab.
bool inside(const std::string& folder, const std::string& file) {
    namespace fs = std::filesystem;
    std::error_code error;
    fs::path root = fs::weakly_canonical(fs::absolute(folder.empty() ? "." : folder, error), error);
    if (error) {
        return false;
    }
    fs::path target = fs::weakly_canonical(fs::absolute(file, error), error);
    if (error) {
        return false;
    }
    auto t = target.begin();
    for (const fs::path& part : root) {
        if (part.empty()) {
            continue;  // a trailing separator
        }
        if (t == target.end() || *t != part) {
            return false;
        }
        ++t;
    }
    return true;
}

}  // namespace

void checkNamedFile(const std::string& modelPath, const std::string& file, const char* what, const PathPolicy& paths) {
    if (!paths.allowOutside && !inside(folderOf(modelPath), file)) {
        throw InputError(modelPath + ": " + what + " " + quote(file) +
                         " lies outside the model's folder (--allow-outside-paths reads it)");
    }
}

FileReader defaultFileReader() {
    return [](const std::string& path, const char* what) { return readInputFile(path, kModelFileLimit, what); };
}

bool isModelFile(const std::string& path) {
    std::string ext = lowerExtension(path);
    return ext == "obj" || ext == "gltf" || ext == "glb";
}

ModelExtras addModel(Scene& scene, const std::string& path, const std::string& bytes, const ModelOptions& options,
                     const FileReader& read) {
    std::string ext = lowerExtension(path);
    std::size_t triangles = scene.triangles.size();
    std::uint64_t dropped = scene.droppedTriangles;
    ModelExtras extras;
    if (ext == "obj") {
        extras = addObjModel(scene, path, bytes, options, read);
    } else if (ext == "gltf" || ext == "glb") {
        extras = addGltfModel(scene, path, bytes, options, read);
    } else {
        throw InputError(path + ": not a model file Photon reads (.obj, .gltf, .glb)");
    }
    // A model that brings nothing to render is an error, not a black image (or, in a scene of
    // nothing else, an automatic radius of 0): whatever the loader says about why.
    if (scene.triangles.size() == triangles) {
        std::uint64_t lost = scene.droppedTriangles - dropped;
        throw InputError(path + (lost > 0 ? ": no triangles: all " + std::to_string(lost) + " have no area or are not finite"
                                          : std::string(": no triangles to render")));
    }
    // A vertex or a node's transform far off (1e30) would make every automatic radius infinite.
    glm::vec3 lo(FLOAT_MAX);
    glm::vec3 hi(-FLOAT_MAX);
    for (std::size_t i = triangles; i < scene.triangles.size(); ++i) {
        const Triangle& t = scene.triangles[i];
        lo = glm::min(lo, glm::min(t.v0, glm::min(t.v1, t.v2)));
        hi = glm::max(hi, glm::max(t.v0, glm::max(t.v1, t.v2)));
    }
    if (widestSpan(lo, hi) > kMaxSceneSpan) {
        throw InputError(path + ": the model's triangles are " + describeSpan(lo, hi) + ", wider than the " +
                         formatNumber(kMaxSceneSpan) + " Photon renders (a vertex or a node's transform far off?)");
    }
    return extras;
}

ModelExtras addModelFile(Scene& scene, const std::string& path, const ModelOptions& options) {
    FileReader read = defaultFileReader();
    return addModel(scene, path, read(path, "model file"), options, read);
}

Scene loadModelScene(const std::string& path, const PathPolicy& paths) {
    FileReader read = defaultFileReader();
    return loadModelScene(path, read(path, "model file"), read, paths);
}

Scene loadModelScene(const std::string& path, const std::string& bytes, const FileReader& read, const PathPolicy& paths) {
    Scene scene;
    std::size_t slash = path.find_last_of('/');
    scene.name = slash == std::string::npos ? path : path.substr(slash + 1);
    ModelOptions options;
    options.cameraAndLights = true;
    options.paths = paths;
    ModelExtras extras = addModel(scene, path, bytes, options, read);
    if (scene.droppedTriangles > 0) {
        scene.warnings.push_back(path + ": " + droppedMessage(scene.droppedTriangles));
    }
    // The camera, if the file has none, frames the bounds: from the front, a little above, the
    // bounding sphere filling the vertical field of view.
    scene.finalize();
    glm::vec3 centre = 0.5f * (scene.boundsMin + scene.boundsMax);
    float radius = std::max(0.5f * glm::length(scene.boundsMax - scene.boundsMin), 1e-6f);
    if (extras.hasCamera) {
        scene.camera = extras.camera;
    } else {
        scene.camera.fovY = 40.0f;
        float distance = radius / std::sin(0.5f * glm::radians(scene.camera.fovY)) * 1.05f;
        scene.camera.position = centre + glm::normalize(glm::vec3(0.35f, 0.3f, 1.0f)) * distance;
        scene.camera.lookAt = centre;
        scene.camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    }
    // The model's own lights, or the studio's. Punctual lights (KHR_lights_punctual) are the
    // author's lighting and light the model alone. Emissive surfaces alone do only if they carry
    // most of the power: more than the sun and the studio would pour onto the model's bounding
    // sphere (sun E + studio πL over its cross-section πr²); labels, LEDs and screens (assimp's
    // ClearCoatTest) glow under the studio lights instead of rendering black on black. A surface's
    // power is taken from its emissive factor, an upper bound where a texture darkens it.
    double emitted = 0.0;
    for (const Light& l : scene.lights) {
        emitted += l.type == LIGHT_TRIANGLES ? (double(l.power.x) + double(l.power.y) + double(l.power.z)) / 3.0 : 0.0;
    }
    double studioPower = (kStudioSunIrradiance + PI * kStudioRadiance) * PI * double(radius) * double(radius);
    if (extras.lights == 0 && emitted <= studioPower) {
        glm::vec3 forward = glm::normalize(scene.camera.lookAt - scene.camera.position);
        glm::vec3 side = glm::cross(forward, scene.camera.up);
        if (!(glm::length(side) > 1e-6f)) {  // a glTF camera looking along its up vector
            side = glm::cross(forward, std::abs(forward.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1));
        }
        glm::vec3 right = glm::normalize(side);
        glm::vec3 up = glm::cross(right, forward);
        scene.addDirectionalLight(glm::normalize(forward + 0.6f * right - 1.2f * up), glm::vec3(kStudioSunIrradiance));
        EnvironmentLight studio;
        studio.source = "studio";
        studio.map = makeStudioMap();
        studio.radiance = glm::vec3(kStudioRadiance);
        studio.lights = true;
        scene.setEnvironment(std::move(studio));
    }
    scene.finalize();
    return scene;
}

}  // namespace photon
