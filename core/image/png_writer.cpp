#include "core/image/png_writer.h"

#include <algorithm>
#include <memory>
#include <vector>

#include <isa-l/igzip_lib.h>
#include <zlib.h>

#include "core/system/error.h"
#include "core/system/parallel.h"

namespace photon {
namespace {

// Rows per band: the bands, and so the file's bytes, do not depend on the number of threads.
constexpr std::uint32_t kBandRows = 32;
// igzip's working memory for level 1, its default size.
constexpr std::uint32_t kLevelBufferBytes = ISAL_DEF_LVL1_DEFAULT;

void putU32(unsigned char* at, std::uint32_t v) {
    at[0] = static_cast<unsigned char>(v >> 24);
    at[1] = static_cast<unsigned char>(v >> 16);
    at[2] = static_cast<unsigned char>(v >> 8);
    at[3] = static_cast<unsigned char>(v);
}

// A chunk: length, type, data, then the CRC-32 of type and data.
std::string chunk(const char* type, const std::string& data) {
    std::string c(12 + data.size(), '\0');
    auto* bytes = reinterpret_cast<unsigned char*>(c.data());
    putU32(bytes, std::uint32_t(data.size()));
    std::copy(type, type + 4, c.begin() + 4);
    std::copy(data.begin(), data.end(), c.begin() + 8);
    putU32(bytes + 8 + data.size(), std::uint32_t(crc32(0L, bytes + 4, uInt(4 + data.size()))));
    return c;
}

std::string u32s(std::initializer_list<std::uint32_t> values) {
    std::string s(4 * values.size(), '\0');
    unsigned char* at = reinterpret_cast<unsigned char*>(s.data());
    for (std::uint32_t v : values) {
        putU32(at, v);
        at += 4;
    }
    return s;
}

// One band: its IDAT chunk, whole, and the Adler-32 of its filtered rows for the stream's end.
struct Band {
    std::string chunk;
    std::uint32_t adler = 1;
    std::size_t rawBytes = 0;
};

// The zlib stream's header: deflate with a 32K window, fastest level (it goes first in band 0).
constexpr unsigned char kZlibHeader[2] = {0x78, 0x01};

Band encodeBand(std::uint32_t width, std::uint32_t y0, std::uint32_t y1, bool first, bool last,
                const PngRowSource& rows) {
    std::size_t stride = 1 + std::size_t(width) * 3;  // the filter byte, then the row
    std::vector<unsigned char> raw(stride * (y1 - y0));
    for (std::uint32_t y = y0; y < y1; ++y) {
        unsigned char* line = &raw[stride * (y - y0)];
        rows(y, line + 1);
        // Sub: each byte minus the same channel of the pixel to its left, from the right end.
        for (std::size_t i = stride - 1; i > 3; --i) {
            line[i] = static_cast<unsigned char>(line[i] - line[i - 3]);
        }
        line[0] = 1;
    }
    Band band;
    band.rawBytes = raw.size();
    band.adler = isal_adler32(1, raw.data(), raw.size());

    // The chunk is built in place: length and type, [zlib header], deflate data, CRC.
    std::size_t head = 8 + (first ? 2 : 0);
    band.chunk.resize(head + raw.size() + raw.size() / 8 + 1024);
    std::unique_ptr<std::uint8_t[]> levelBuffer(new std::uint8_t[kLevelBufferBytes]);  // not cleared: scratch
    isal_zstream z;
    isal_deflate_init(&z);
    z.level = 1;
    z.level_buf = levelBuffer.get();
    z.level_buf_size = kLevelBufferBytes;
    z.next_in = raw.data();
    z.avail_in = std::uint32_t(raw.size());
    // A sync flush ends the band byte-aligned, without the final-block bit; the last band ends
    // the deflate stream.
    z.flush = last ? NO_FLUSH : SYNC_FLUSH;
    z.end_of_stream = last ? 1 : 0;
    for (;;) {
        std::size_t used = head + z.total_out;
        z.next_out = reinterpret_cast<std::uint8_t*>(band.chunk.data()) + used;
        z.avail_out = std::uint32_t(band.chunk.size() - used);
        if (isal_deflate(&z) != COMP_OK) {
            throw RuntimeError("cannot encode the PNG image: the deflate encoder failed");
        }
        // Everything is out once output space is left over (or, at the end, the stream is closed).
        bool done = last ? z.internal_state.state == ZSTATE_END : z.avail_in == 0 && z.avail_out > 0;
        if (done) {
            break;
        }
        band.chunk.resize(band.chunk.size() * 2);
    }
    std::size_t data = head - 8 + z.total_out;
    band.chunk.resize(8 + data + 4);
    auto* bytes = reinterpret_cast<unsigned char*>(band.chunk.data());
    putU32(bytes, std::uint32_t(data));
    std::copy("IDAT", "IDAT" + 4, bytes + 4);
    if (first) {
        std::copy(kZlibHeader, kZlibHeader + 2, bytes + 8);
    }
    putU32(bytes + 8 + data, std::uint32_t(crc32(0L, bytes + 4, uInt(4 + data))));
    return band;
}

}  // namespace

std::string encodePng(std::uint32_t width, std::uint32_t height, const PngRowSource& rows) {
    if (width == 0 || height == 0 || std::uint64_t(width) * 3 + 1 > 0x7fffffffu / kBandRows) {
        throw RuntimeError("cannot encode a PNG image of " + std::to_string(width) + "x" + std::to_string(height));
    }
    std::uint32_t bandCount = (height + kBandRows - 1) / kBandRows;
    std::vector<Band> bands(bandCount);
    parallelFor(bandCount, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b) {
            std::uint32_t y0 = std::uint32_t(b) * kBandRows;
            bands[b] = encodeBand(width, y0, std::min(height, y0 + kBandRows), b == 0, b + 1 == bandCount, rows);
        }
    });

    // IHDR: size, 8 bits per sample, colour type 2 (RGB), deflate, adaptive filtering, no interlace.
    std::string header = u32s({width, height}) + std::string("\x08\x02\x00\x00\x00", 5);
    std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header);
    // The bytes are sRGB-encoded (perceptual intent), with the gAMA and cHRM that the PNG
    // specification recommends beside sRGB for decoders that do not know it (11.3.3.5).
    png += chunk("sRGB", std::string(1, '\0'));
    png += chunk("gAMA", u32s({45455}));
    png += chunk("cHRM", u32s({31270, 32900, 64000, 33000, 30000, 60000, 15000, 6000}));
    // The bands' IDAT chunks in order, then the zlib stream's end, the Adler-32 of every band's
    // filtered rows, in one more.
    std::size_t size = png.size() + 2 * 16;
    for (const Band& b : bands) {
        size += b.chunk.size();
    }
    png.reserve(size);
    uLong adler = adler32(0L, nullptr, 0);
    for (Band& b : bands) {
        png += b.chunk;
        adler = adler32_combine(adler, b.adler, z_off_t(b.rawBytes));
        std::string().swap(b.chunk);
    }
    png += chunk("IDAT", u32s({std::uint32_t(adler)}));
    png += chunk("IEND", "");
    return png;
}

}  // namespace photon
