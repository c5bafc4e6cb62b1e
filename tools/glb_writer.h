// A mesh as binary glTF (.glb): positions, normals and indices in one buffer, one mesh, one node,
// one material. For photon-make-mesh's benchmark meshes and the tests.
#pragma once

#include <string>

#include "core/scene/mesh.h"

namespace photon::tools {

// `material` is a glTF material object as JSON text, e.g. {"pbrMetallicRoughness": {...}}.
std::string glbFromMesh(const Mesh& mesh, const std::string& material);

}  // namespace photon::tools
