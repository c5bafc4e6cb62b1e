// Environment maps from files (issue 18, light from the sky): equirectangular images of linear
// radiance, Radiance RGBE (.hdr, decoded by stb_image) or scanline OpenEXR (.exr, by tinyexr),
// told apart by their first bytes. The size a header states is checked before any pixel is
// decoded, and the pixel data is checked to be whole before a decoder reads it: on a short file
// stb_image makes up zeros (or loops forever inside a run-length scanline), and tinyexr leaves the
// lines of a chunk it does not find as uninitialised memory.
#pragma once

#include <cstdint>
#include <string>

#include "core/scene/environment.h"
#include "core/scene/scene.h"
#include "core/system/numbers.h"

namespace photon {

// The cap on environment map files: 3 GiB, room for the largest map (kEnvironmentWidthMax ×
// kEnvironmentHeightMax texels) as uncompressed 32-bit RGBA OpenEXR (2 GiB).
inline constexpr std::uint64_t kEnvironmentFileLimit = std::uint64_t(3) << 30;

// The map in the file at `path`, row 0 the image's top row (the zenith), in linear RGB. Throws
// InputError "<path>: <reason>" for a file that cannot be read (core/system/input_file.h), is
// neither a Radiance HDR nor an OpenEXR image (naming the file's extension), states a size
// outside 1×1 … kEnvironmentWidthMax × kEnvironmentHeightMax, is truncated or corrupt, or holds a
// texel that is not finite or is negative (radiance is neither).
EnvironmentMap loadEnvironmentMap(const std::string& path);

// What photon-render's --environment-intensity and Python's environment_intensity accept.
inline constexpr Range kEnvironmentIntensity{0.0, 1e12};

// Lights `scene` with the map at `path` (replacing its environment or background, finalizing the
// scene again), its texels times `intensity`; a refusal names `where` (an option or keyword).
void lightWithEnvironmentMap(Scene& scene, const std::string& path, float intensity, const std::string& where);

// The same from the file's bytes (read by the caller: a scene's FileReader), `path` naming it.
EnvironmentMap decodeEnvironmentMap(const std::string& bytes, const std::string& path);

}  // namespace photon
