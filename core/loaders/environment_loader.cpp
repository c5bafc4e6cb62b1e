#include "core/loaders/environment_loader.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <memory>

#include <stb_image.h>
#include <tinyexr.h>

#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "core/system/input_file.h"

namespace photon {
namespace {

using u64 = std::uint64_t;
constexpr std::size_t kNone = std::string::npos;

unsigned char byteAt(const std::string& b, std::size_t at) { return static_cast<unsigned char>(b[at]); }

u64 littleEndian(const std::string& b, std::size_t at, int bytes) {
    u64 x = 0;
    for (int i = bytes; i-- > 0;) {
        x = (x << 8) | byteAt(b, at + std::size_t(i));
    }
    return x;
}

bool startsWith(const std::string& b, const char* prefix, std::size_t length) {
    return b.size() >= length && b.compare(0, length, prefix, length) == 0;
}

// The file name's extension as written ("" if it has none), for the message about a wrong format.
std::string extensionOf(const std::string& path) {
    std::size_t dot = path.find_last_of('.');
    std::size_t slash = path.find_last_of('/');
    return dot == kNone || (slash != kNone && dot < slash) ? "" : path.substr(dot);
}

// Refuses a stated size outside 1×1 … the maxima, before anything is allocated for it.
void checkSize(const std::string& path, std::int64_t width, std::int64_t height) {
    if (width < 1 || height < 1 || width > std::int64_t(kEnvironmentWidthMax) || height > std::int64_t(kEnvironmentHeightMax)) {
        throw InputError(path + ": a map of " + std::to_string(width) + "x" + std::to_string(height) +
                         " texels; environment maps are 1x1 to " + std::to_string(kEnvironmentWidthMax) + "x" +
                         std::to_string(kEnvironmentHeightMax));
    }
}

// ---- Radiance RGBE (.hdr) ------------------------------------------------------------------------
// A text header ("#?RADIANCE", lines of variables, an empty line), a resolution line ("-Y height
// +X width": rows from the top), then 4 bytes a texel (red, green, blue mantissas and a shared
// exponent), each scanline of 8 to 32767 texels usually run-length encoded channel by channel.

// Where the pixels start: past the header, which stb_image ends at the first empty line (or at a
// line that begins with a NUL byte), and past the resolution line after it. kNone if the file
// ends first.
std::size_t rgbePixelStart(const std::string& b) {
    std::size_t end = b.find('\n');  // of the "#?RADIANCE" line
    for (bool last = false; !last;) {
        if (end == kNone || end + 1 >= b.size()) {
            return kNone;
        }
        last = b[end + 1] == '\n' || b[end + 1] == '\0';
        end = b.find('\n', end + 1);
    }
    std::size_t resolutionEnd = end == kNone ? kNone : b.find('\n', end + 1);
    return resolutionEnd == kNone ? kNone : resolutionEnd + 1;
}

// Where the pixel data of a width × height image that starts at `at` ends, found by walking it as
// stbi__hdr_load reads it, without decoding: a scanline of 8 to 32767 texels begins 2, 2, then its
// width in two bytes, and holds each channel in turn as runs (128 + n, then the value n times)
// and dumps (n, then n values); other widths are flat, 4 bytes a texel, and so is the rest of the
// image from a scanline without that marker on. Throws InputError if the data stops early
// (stb_image would make up zeros, or never leave a run of zero length) or a run overflows its row.
std::size_t rgbePixelEnd(const std::string& b, std::size_t at, u64 width, u64 height, const std::string& path) {
    auto truncated = [&](u64 row) {
        return InputError(path + ": truncated HDR file: the pixels stop in row " + std::to_string(row) + " of " +
                          std::to_string(height));
    };
    // stb_image reads the image flat from its first texel on, wherever it notices that it is flat.
    auto flat = [&]() {
        if ((b.size() - at) / 4 < width * height) {
            throw truncated((b.size() - at) / 4 / width);
        }
        return at + 4 * width * height;
    };
    if (width < 8 || width >= 32768) {
        return flat();
    }
    for (u64 y = 0; y < height; ++y) {
        if (b.size() - at < 4) {
            throw truncated(y);
        }
        if (byteAt(b, at) != 2 || byteAt(b, at + 1) != 2 || (byteAt(b, at + 2) & 0x80) != 0) {
            return flat();
        }
        u64 stated = u64(byteAt(b, at + 2)) << 8 | byteAt(b, at + 3);
        if (stated != width) {
            throw InputError(path + ": corrupt HDR file: row " + std::to_string(y) + " says it holds " +
                             std::to_string(stated) + " texels, not " + std::to_string(width));
        }
        at += 4;
        for (int channel = 0; channel < 4; ++channel) {
            for (u64 x = 0; x < width;) {
                if (at >= b.size()) {
                    throw truncated(y);
                }
                u64 count = byteAt(b, at++);
                bool run = count > 128;
                count -= run ? 128 : 0;
                if (count > width - x) {
                    throw InputError(path + ": corrupt HDR file: a run-length code overflows row " + std::to_string(y));
                }
                u64 bytes = run ? 1 : count;
                if (b.size() - at < bytes) {
                    throw truncated(y);
                }
                at += std::size_t(bytes);
                x += count;
            }
        }
    }
    return at;
}

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "texels are 3 packed floats, as stb_image writes them");

EnvironmentMap decodeHdr(const std::string& b, const std::string& path) {
    auto reason = [] { return std::string(stbi_failure_reason() ? stbi_failure_reason() : "unknown error"); };
    const auto* data = reinterpret_cast<const stbi_uc*>(b.data());
    std::size_t start = rgbePixelStart(b);
    if (start == kNone) {
        throw InputError(path + ": truncated HDR file: it ends in its header");
    }
    int width = 0;
    int height = 0;
    int channels = 0;
    if (!stbi_info_from_memory(data, int(std::min<std::size_t>(b.size(), INT_MAX)), &width, &height, &channels)) {
        throw InputError(path + ": a Radiance header stb_image does not read (it reads FORMAT=32-bit_rle_rgbe, "
                                "then the resolution line \"-Y height +X width\")");
    }
    checkSize(path, width, height);
    // stb_image is handed exactly the bytes it decodes, so it never runs past them.
    std::size_t end = rgbePixelEnd(b, start, u64(width), u64(height), path);
    if (end > std::size_t(INT_MAX)) {
        throw InputError(path + ": HDR file whose pixels end beyond its first 2 GiB");
    }
    int w = 0;
    int h = 0;
    std::unique_ptr<float, void (*)(void*)> pixels(stbi_loadf_from_memory(data, int(end), &w, &h, &channels, 3),
                                                   stbi_image_free);
    if (!pixels || w != width || h != height) {
        throw InputError(path + ": cannot decode the HDR file: " + reason());
    }
    EnvironmentMap map{std::uint32_t(width), std::uint32_t(height), {}};
    map.texels.resize(std::size_t(width) * std::size_t(height));
    std::memcpy(map.texels.data(), pixels.get(), map.texels.size() * sizeof(glm::vec3));
    return map;
}

// ---- OpenEXR (.exr) ------------------------------------------------------------------------------
// The magic number and version (8 bytes), a header of attributes (channels, compression, data
// window, line order, …), a table of offsets, one per chunk of scanlines, then the chunks: each
// the number of its first line, its length, and its lines (compressed or not), channels apart.

// tinyexr's structs, freed on every way out.
struct ExrHeader : EXRHeader {
    ExrHeader() { InitEXRHeader(this); }
    ~ExrHeader() { FreeEXRHeader(this); }
    ExrHeader(const ExrHeader&) = delete;
    ExrHeader& operator=(const ExrHeader&) = delete;
};
struct ExrImage : EXRImage {
    ExrImage() { InitEXRImage(this); }
    ~ExrImage() { FreeEXRImage(this); }
    ExrImage(const ExrImage&) = delete;
    ExrImage& operator=(const ExrImage&) = delete;
};

// tinyexr's message (lines of it) as one line, freed.
std::string exrReason(const char* err) {
    std::string text = err ? err : "unknown error";
    FreeEXRErrorMessage(err);
    std::string line;
    for (char c : text) {
        if (c != '\n' && c != '\r') {
            line += c;
        } else if (!line.empty() && line.back() != ' ') {
            line += "; ";
        }
    }
    while (!line.empty() && (line.back() == ' ' || line.back() == ';')) {
        line.pop_back();
    }
    return printable(line);
}

// Scanlines a chunk holds for each compression tinyexr decodes; 0 for the others.
std::int64_t linesPerChunk(int compression) {
    switch (compression) {
        case TINYEXR_COMPRESSIONTYPE_NONE:
        case TINYEXR_COMPRESSIONTYPE_RLE:
        case TINYEXR_COMPRESSIONTYPE_ZIPS: return 1;
        case TINYEXR_COMPRESSIONTYPE_ZIP: return 16;
        case TINYEXR_COMPRESSIONTYPE_PIZ: return 32;
        default: return 0;
    }
}

// tinyexr puts each chunk's lines where the chunk itself says they go (uncompressed: where its
// place in the offset table says), and leaves any line that no chunk fills uninitialised. So before
// it decodes, the offset table must be whole, and chunk k must lie inside the file and hold the
// lines from min_y + k·n: what the OpenEXR specification asks of a scanline file anyway.
void checkExrChunks(const std::string& b, const EXRHeader& header, std::int64_t height, const std::string& path) {
    std::int64_t lines = linesPerChunk(header.compression_type);
    u64 chunks = u64((height + lines - 1) / lines);
    auto truncated = [&](const std::string& what) { return InputError(path + ": truncated EXR file: " + what); };
    if (header.chunk_count > 0 && u64(header.chunk_count) != chunks) {
        throw InputError(path + ": corrupt EXR file: its chunkCount is " + std::to_string(header.chunk_count) + ", not the " +
                         std::to_string(chunks) + " its data window needs");
    }
    u64 table = 8 + u64(header.header_len);
    if (table > b.size() || (b.size() - table) / 8 < chunks) {
        throw truncated("it ends in its offset table");
    }
    for (u64 k = 0; k < chunks; ++k) {
        u64 offset = littleEndian(b, std::size_t(table + 8 * k), 8);
        std::string chunk = "chunk " + std::to_string(k) + " of " + std::to_string(chunks);
        if (offset > b.size() || b.size() - offset < 8) {
            throw truncated(chunk + " begins beyond the end of the file");
        }
        auto first = std::int64_t(std::int32_t(std::uint32_t(littleEndian(b, std::size_t(offset), 4))));
        if (first != std::int64_t(header.data_window.min_y) + std::int64_t(k) * lines) {
            throw InputError(path + ": corrupt EXR file: " + chunk + " holds line " + std::to_string(first) + ", not " +
                             std::to_string(std::int64_t(header.data_window.min_y) + std::int64_t(k) * lines));
        }
        if (b.size() - offset - 8 < littleEndian(b, std::size_t(offset + 4), 4)) {
            throw truncated(chunk + " ends beyond the end of the file");
        }
    }
}

EnvironmentMap decodeExr(const std::string& b, const std::string& path) {
    const auto* data = reinterpret_cast<const unsigned char*>(b.data());
    EXRVersion version{};
    if (ParseEXRVersionFromMemory(&version, data, b.size()) != TINYEXR_SUCCESS) {
        throw InputError(path + ": not an OpenEXR file tinyexr reads (truncated, or not version 2)");
    }
    if (version.multipart || version.non_image) {
        throw InputError(path + ": a multi-part or deep EXR file; environment maps are single-part scanline images");
    }
    if (version.tiled) {
        throw InputError(path + ": a tiled EXR file; environment maps are scanline images (save it without tiles)");
    }
    ExrHeader header;
    const char* err = nullptr;
    if (ParseEXRHeaderFromMemory(&header, &version, data, b.size(), &err) != TINYEXR_SUCCESS) {
        throw InputError(path + ": cannot read the EXR header: " + exrReason(err));
    }
    const EXRBox2i& window = header.data_window;
    std::int64_t width = std::int64_t(window.max_x) - window.min_x + 1;
    std::int64_t height = std::int64_t(window.max_y) - window.min_y + 1;
    checkSize(path, width, height);
    // Neither happens after tinyexr's parse (it reads tiles only under the version's flag and
    // refuses other compressions), but the chunk checks below rely on both.
    if (header.tiled || linesPerChunk(header.compression_type) == 0) {
        throw InputError(path + ": an EXR file tinyexr does not decode (tiled, or compression " +
                         std::to_string(header.compression_type) + ")");
    }

    // Red, green and blue by name, as half or 32-bit floats; other channels (alpha) are decoded and
    // ignored. tinyexr reads every channel as if sampled once per texel, so none may be subsampled.
    int rgb[3] = {-1, -1, -1};
    for (int c = 0; c < header.num_channels; ++c) {
        const EXRChannelInfo& channel = header.channels[c];
        if (channel.x_sampling != 1 || channel.y_sampling != 1) {
            throw InputError(path + ": EXR channel " + quote(channel.name) + " is subsampled; Photon reads full-resolution channels");
        }
        for (int k = 0; k < 3; ++k) {
            if (std::strcmp(channel.name, k == 0 ? "R" : k == 1 ? "G" : "B") == 0) {
                rgb[k] = c;
            }
        }
        if (header.pixel_types[c] == TINYEXR_PIXELTYPE_HALF) {
            header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
        }
    }
    for (int k = 0; k < 3; ++k) {
        int type = rgb[k] < 0 ? -1 : header.pixel_types[rgb[k]];
        if (type != TINYEXR_PIXELTYPE_HALF && type != TINYEXR_PIXELTYPE_FLOAT) {
            throw InputError(path + ": the EXR file has no " + (k == 0 ? "R" : k == 1 ? "G" : "B") +
                             " channel of half or 32-bit floats; environment maps are RGB or RGBA images");
        }
    }
    if (u64(width) * u64(height) * u64(header.num_channels) > u64(kEnvironmentWidthMax) * kEnvironmentHeightMax * 4) {
        throw InputError(path + ": an EXR file of " + std::to_string(header.num_channels) +
                         " channels, more than Photon decodes at its size");
    }
    checkExrChunks(b, header, height, path);

    // When decoding fails, tinyexr frees the image's buffers itself, channel by channel up to the
    // image's num_channels, which it sets only on success: so the count is set here, and after a
    // failure the struct is forgotten rather than freed twice.
    ExrImage image;
    image.num_channels = header.num_channels;
    if (LoadEXRImageFromMemory(&image, &header, data, b.size(), &err) != TINYEXR_SUCCESS) {
        InitEXRImage(&image);
        throw InputError(path + ": corrupt EXR file: " + exrReason(err));
    }
    if (image.images == nullptr || image.width != width || image.height != height) {
        throw InputError(path + ": corrupt EXR file: tinyexr decoded no image of its data window");
    }
    // tinyexr stores the lines of a file whose lineOrder is not INCREASING_Y bottom up, though the
    // line order only says in which order the chunks lie in the file (each names its lines): such a
    // file is read back from its last row.
    bool flipped = header.line_order != 0;
    EnvironmentMap map{std::uint32_t(width), std::uint32_t(height), {}};
    map.texels.resize(std::size_t(width) * std::size_t(height));
    for (std::size_t y = 0; y < map.height; ++y) {
        std::size_t row = (flipped ? map.height - 1 - y : y) * map.width;
        for (std::size_t x = 0; x < map.width; ++x) {
            glm::vec3& t = map.texels[y * map.width + x];
            for (int k = 0; k < 3; ++k) {
                t[k] = reinterpret_cast<const float*>(image.images[rgb[k]])[row + x];
            }
        }
    }
    return map;
}

// Radiance is finite and never negative; the first texel that is not names itself.
void checkTexels(const EnvironmentMap& map, const std::string& path) {
    for (std::size_t i = 0; i < map.texels.size(); ++i) {
        glm::vec3 c = map.texels[i];
        auto where = [&] { return "texel (" + std::to_string(i % map.width) + ", " + std::to_string(i / map.width) + ")"; };
        if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) {
            throw InputError(path + ": " + where() + " is not finite");
        }
        if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) {
            throw InputError(path + ": " + where() + " is negative (" + formatNumber(c.x) + ", " + formatNumber(c.y) + ", " +
                             formatNumber(c.z) + "): radiance cannot be negative");
        }
    }
}

}  // namespace

EnvironmentMap loadEnvironmentMap(const std::string& path) {
    return decodeEnvironmentMap(readInputFile(path, kEnvironmentFileLimit, "environment map"), path);
}

EnvironmentMap decodeEnvironmentMap(const std::string& bytes, const std::string& path) {
    EnvironmentMap map;
    if (bytes.empty()) {
        throw InputError(path + ": empty file, not an environment map");
    }
    if (startsWith(bytes, "#?RADIANCE", 10) || startsWith(bytes, "#?RGBE", 6)) {
        map = decodeHdr(bytes, path);
    } else if (startsWith(bytes, "\x76\x2f\x31\x01", 4)) {
        map = decodeExr(bytes, path);
    } else {
        std::string extension = extensionOf(path);
        throw InputError(path + ": neither a Radiance HDR nor an OpenEXR image (by its first bytes), though its name " +
                         (extension.empty() ? "has no extension" : "ends in " + quote(extension)) +
                         "; environment maps are .hdr or .exr files");
    }
    checkTexels(map, path);
    return map;
}

void lightWithEnvironmentMap(Scene& scene, const std::string& path, float intensity, const std::string& where) {
    EnvironmentLight env;
    env.source = path;
    try {
        env.map = loadEnvironmentMap(path);
    } catch (const InputError& e) {
        throw InputError(where + ": " + e.what());
    }
    env.radiance = glm::vec3(intensity);
    env.lights = true;
    scene.setEnvironment(std::move(env));
    scene.finalize();
}

}  // namespace photon
