#include "environment_files.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <tinyexr.h>

// stb_image_write compiled in, all of it static: the tests link libdraco's archive, whose tinygltf
// also defines stb_image_write's functions and would be linked in to provide them (and with them
// its tinygltf, in place of libtinygltf's; see core/CMakeLists.txt).
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

namespace photon::tools {

static_assert(int(ExrType::Half) == TINYEXR_PIXELTYPE_HALF && int(ExrType::Float) == TINYEXR_PIXELTYPE_FLOAT);
static_assert(int(ExrCompression::Rle) == TINYEXR_COMPRESSIONTYPE_RLE && int(ExrCompression::Piz) == TINYEXR_COMPRESSIONTYPE_PIZ);

std::string hdrBytes(int width, int height, const std::vector<glm::vec3>& texels) {
    std::string bytes;
    auto append = [](void* context, void* data, int size) { static_cast<std::string*>(context)->append(static_cast<char*>(data), std::size_t(size)); };
    if (!stbi_write_hdr_to_func(append, &bytes, width, height, 3, &texels.at(0).x)) {
        throw std::runtime_error("stb_image_write wrote no HDR file");
    }
    return bytes;
}

std::string exrBytes(int width, int height, const std::vector<glm::vec3>& texels, std::string channels, ExrType type,
                     ExrCompression compression) {
    std::sort(channels.begin(), channels.end());
    std::size_t n = channels.size();
    std::vector<std::vector<float>> planes(n);
    std::vector<float*> pointers;
    std::vector<EXRChannelInfo> info(n);
    std::vector<int> given(n, TINYEXR_PIXELTYPE_FLOAT);
    std::vector<int> stored(n, int(type));
    for (std::size_t c = 0; c < n; ++c) {
        int k = int(std::string("RGB").find(channels[c]));
        for (const glm::vec3& t : texels) {
            planes[c].push_back(k < 0 ? 0.5f : t[k]);
        }
        pointers.push_back(planes[c].data());
        info[c].name[0] = channels[c];
    }
    EXRImage image;
    InitEXRImage(&image);
    image.num_channels = int(n);
    image.images = reinterpret_cast<unsigned char**>(pointers.data());
    image.width = width;
    image.height = height;
    EXRHeader header;
    InitEXRHeader(&header);
    header.compression_type = int(compression);
    header.num_channels = int(n);
    header.channels = info.data();
    header.pixel_types = given.data();
    header.requested_pixel_types = stored.data();
    unsigned char* memory = nullptr;
    const char* err = nullptr;
    std::size_t size = SaveEXRImageToMemory(&image, &header, &memory, &err);
    if (size == 0) {
        std::string reason = err ? err : "unknown error";
        FreeEXRErrorMessage(err);
        throw std::runtime_error("tinyexr wrote no EXR file: " + reason);
    }
    std::string bytes(reinterpret_cast<const char*>(memory), size);
    std::free(memory);
    return bytes;
}

std::size_t exrAttribute(const std::string& bytes, const std::string& name, const std::string& type) {
    std::size_t at = bytes.find(name + '\0' + type + '\0');
    if (at == std::string::npos) {
        throw std::runtime_error("no EXR attribute " + name);
    }
    return at + name.size() + type.size() + 2 + 4;  // past the two names and the value's size
}

std::size_t exrChunk(const std::string& bytes, std::size_t k) {
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    EXRVersion version;
    EXRHeader header;
    InitEXRHeader(&header);
    if (ParseEXRVersionFromMemory(&version, data, bytes.size()) != TINYEXR_SUCCESS ||
        ParseEXRHeaderFromMemory(&header, &version, data, bytes.size(), nullptr) != TINYEXR_SUCCESS) {
        FreeEXRHeader(&header);
        throw std::runtime_error("not an EXR file tinyexr reads");
    }
    std::uint64_t offset = 0;
    std::memcpy(&offset, bytes.data() + 8 + header.header_len + 8 * k, 8);  // the table follows the header
    FreeEXRHeader(&header);
    return std::size_t(offset);
}

}  // namespace photon::tools
