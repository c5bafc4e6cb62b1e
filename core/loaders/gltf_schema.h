// The types of a glTF 2.0 document's values, checked against the specification's JSON schema
// before tinygltf reads it. tinygltf passes over a value of the wrong type as if it were absent: a
// material whose pbrMetallicRoughness is an array, or a texture index of -1, loses its texture and
// the file renders without a word. Here every property the schema gives a type (objects, arrays of
// objects, strings, numbers, booleans, glTFids and counts, which are non-negative integers), and the
// fields of the extensions the loader reads, must have that type, or the file is refused with its
// JSON pointer:
//   model.gltf: /materials/0/pbrMetallicRoughness: must be an object, not an array
// Properties the schema does not name are ignored (glTF allows them), and so are values of the right
// type out of their range: the loader checks those where it uses them.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace photon {

// Throws InputError "<path>: <JSON pointer>: must be ..., not ..." at the first value of a wrong type.
void checkGltfTypes(const std::string& path, const nlohmann::json& root);

}  // namespace photon
