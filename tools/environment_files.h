// Environment map files for the tests and the fuzz seeds (photon-make-environment-corpus):
// Radiance HDR by stb_image_write, OpenEXR by tinyexr in any of its channel sets, pixel types and
// compressions, from texels listed row by row from the top.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace photon::tools {

// tinyexr's pixel types and compressions, so that callers need not include tinyexr.h.
enum class ExrType { Half = 1, Float = 2 };
enum class ExrCompression { None = 0, Rle = 1, Zips = 2, Zip = 3, Piz = 4 };

// RGBE: run-length encoded for widths 8 to 32767, flat otherwise, as stb_image_write writes it.
std::string hdrBytes(int width, int height, const std::vector<glm::vec3>& texels);

// The channels named in `channels` (some of "RGBA", written in the sorted order the OpenEXR
// specification asks for); alpha is 0.5.
std::string exrBytes(int width, int height, const std::vector<glm::vec3>& texels, std::string channels = "RGB",
                     ExrType type = ExrType::Float, ExrCompression compression = ExrCompression::Zip);

// The place of attribute `name`'s value in an EXR file, and where chunk k begins (its offset).
std::size_t exrAttribute(const std::string& bytes, const std::string& name, const std::string& type);
std::size_t exrChunk(const std::string& bytes, std::size_t k);

}  // namespace photon::tools
