// Scene files: the JSON format of docs/scenes.md, read into a finalized Scene. Every key and value is
// checked; any problem is an InputError "<source>: <JSON pointer>: <reason>".
#pragma once

#include <string>

#include "scene.h"

namespace photon {

// Reads a scene file; throws InputError("<path>: <json pointer>: <reason>") on any problem.
Scene loadSceneFile(const std::string& path);

// Same from text; sourceName is used in messages in place of the path.
Scene loadSceneJson(const std::string& text, const std::string& sourceName);

// The default scene: the Cornell box embedded in the binary.
Scene defaultScene();

}  // namespace photon
