// Model files (Wavefront OBJ with MTL, glTF 2.0 as .gltf or .glb) into a scene: their triangles,
// materials mapped onto Photon's (docs/scenes.md has the table), base-colour textures, and, for
// glTF, cameras and KHR_lights_punctual lights. OBJ is parsed by tinyobjloader and glTF by
// tinygltf (Debian packages); every index, number and buffer range is checked here before anything
// is built, and every problem is an InputError "<file>: <place>: <reason>", the place an OBJ line
// or a glTF JSON pointer.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include <glm/glm.hpp>

#include "core/scene/scene.h"

namespace photon {

// Model files and what they reference (MTL files, images, .bin buffers) are read with this cap.
inline constexpr std::uint64_t kModelFileLimit = std::uint64_t(1) << 30;

// How the loaders read companion files: (path, what) → bytes; the default is readInputFile.
using FileReader = std::function<std::string(const std::string& path, const char* what)>;
FileReader defaultFileReader();

// Where the files a model names (glTF buffers and images, an OBJ's mtllib, an MTL's texture maps)
// may lie: inside the model's folder tree, so that a model from elsewhere cannot read the user's
// other files into a render; or anywhere (photon-render --allow-outside-paths).
struct PathPolicy {
    bool allowOutside = false;
};

struct ModelOptions {
    std::uint32_t material = NONE;  // a scene material for every triangle, instead of the file's
    glm::mat4 transform{1.0f};      // applied after the file's own node transforms
    bool cameraAndLights = false;   // glTF: take the file's camera and lights into the scene
    PathPolicy paths;
};

// What a model brought besides geometry.
struct ModelExtras {
    bool hasCamera = false;
    CameraDesc camera;
    std::uint32_t lights = 0;
};

// Adds the model in `bytes` (the contents of `path`, by extension .obj, .gltf or .glb).
ModelExtras addModel(Scene& scene, const std::string& path, const std::string& bytes, const ModelOptions& options,
                     const FileReader& read);

// The same from the file itself.
ModelExtras addModelFile(Scene& scene, const std::string& path, const ModelOptions& options);

// Whether a path names a model file Photon reads (.obj, .gltf, .glb, any case).
bool isModelFile(const std::string& path);

// A model file as a whole scene: its glTF camera and lights if it has them, otherwise a camera
// that frames its bounds and a light from above the camera's shoulder. Finalized.
Scene loadModelScene(const std::string& path, const PathPolicy& paths = {});
// The same from the file's bytes, reading what it references through `read`.
Scene loadModelScene(const std::string& path, const std::string& bytes, const FileReader& read,
                     const PathPolicy& paths = {});

// The parts of the loaders, in obj_loader.cpp and gltf_loader.cpp.
ModelExtras addObjModel(Scene& scene, const std::string& path, const std::string& text, const ModelOptions& options,
                        const FileReader& read);
ModelExtras addGltfModel(Scene& scene, const std::string& path, const std::string& bytes, const ModelOptions& options,
                         const FileReader& read);

// "N triangles without area (or not finite) dropped", the warning a mesh with some gets.
std::string droppedMessage(std::uint64_t count);

// The folder of a path, for resolving what a file references ("" for a bare name).
std::string folderOf(const std::string& path);

// The file `name` in `folder` (with its trailing '/', or ""), as a model names it: '\' is a
// separator too (models written on Windows say `textures\wood.png`), and `.` and `..` are folded.
std::string namedFile(const std::string& folder, const std::string& name);

// Refuses (InputError "<model>: <what> '<file>' lies outside the model's folder ...") a file that,
// with `..` folded and symbolic links followed, is not inside the model's folder tree, unless the
// policy allows it. Nothing is read, so the message cannot show the file's contents or size.
void checkNamedFile(const std::string& modelPath, const std::string& file, const char* what, const PathPolicy& paths);

}  // namespace photon
