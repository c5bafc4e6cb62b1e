// What a glTF file needs before tinygltf may parse it. tinygltf 2.7 refuses two things that are
// valid glTF: a Draco primitive's index accessor without a buffer view (the decoded faces take its
// place), and EXT_meshopt_compression's fallback buffer, which has a length and no data. This
// pre-pass rewrites exactly those in the JSON (the binary chunk is kept as it is), and says plainly
// when a file is glTF 1.0, which tinygltf reports as "Invalid glTF binary" or as an empty model.
// It also refuses, by name, what tinygltf would pass over or report unreadably: an empty file or a
// .glb shorter than its header, a value of the wrong type (gltf_schema.h), a buffer or image URI
// that is absolute or remote, and a data URI that is not good base64 or holds fewer bytes than its
// buffer's byteLength (tinygltf's message would quote the whole URI, megabytes on one line).
#pragma once

#include <set>
#include <string>

namespace photon {

struct GltfDocument {
    std::string bytes;                 // what tinygltf parses: the file, or it rewritten
    bool binary = false;               // a .glb container
    std::set<int> fallbackBuffers;     // EXT_meshopt_compression fallbacks, now one byte each
};

// Throws InputError "<path>: <reason>" or "<path>: <JSON pointer>: <reason>" for what the comment
// above names; anything else tinygltf reports itself.
GltfDocument prepareGltf(const std::string& path, const std::string& bytes);

}  // namespace photon
