// Scene files: the JSON format of docs/scenes.md, read into a finalized Scene. Every key and value is
// checked; any problem is an InputError "<source>: <JSON pointer>: <reason>".
#pragma once

#include <string>

#include "core/loaders/model_loader.h"
#include "core/scene/scene.h"

namespace photon {

// Reads a scene file, or a model file (.obj, .gltf, .glb) as a scene of its own; throws
// InputError("<path>: <json pointer>: <reason>") on any problem.
// `paths` rules where the files that model files name may lie (model_loader.h).
Scene loadSceneFile(const std::string& path, const PathPolicy& paths = {});

// Same from text; sourceName is used in messages in place of the path, and model files of mesh
// objects are found relative to `folder` (with its trailing '/', or "" for the working folder)
// and read, with what they reference, through `read` (the files on disk by default; the fuzz
// targets pass files held in memory); `paths` says which files a model may name.
Scene loadSceneJson(const std::string& text, const std::string& sourceName, const std::string& folder = "",
                    const FileReader& read = defaultFileReader(), const PathPolicy& paths = {});

// The default scene: the Cornell box embedded in the binary.
Scene defaultScene();

}  // namespace photon
