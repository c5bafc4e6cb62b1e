// Image files: PNG and EXR written by core/image/ decode back to what was written. PNG: every
// chunk's CRC and the zlib stream's Adler-32 check out (zlib inflates it), the sRGB, gAMA and cHRM
// chunks come before the pixels, and stb_image decodes the bytes of shared/tonemap.h's tonemap()
// exactly, over several bands of rows and odd sizes. EXR: float for float through tinyexr (the
// reader) in every compression the writer offers, tiled and in scan lines, and as an environment
// map. The sRGB table against the formula.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <zlib.h>

// stb_image compiled in, all of it static: the tests link libdraco's archive, whose tinygltf also
// defines stb_image's functions and would be linked in to provide them (and with them its tinygltf,
// in place of libtinygltf's; see core/CMakeLists.txt).
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include "core/image/display_bytes.h"
#include "core/image/exr_writer.h"
#include "core/image/image.h"
#include "core/loaders/environment_loader.h"
#include "core/system/output_file.h"
#include "shared/tonemap.h"
#include "temp_folder.h"

namespace photon {
namespace {

namespace fs = std::filesystem;

std::uint32_t readU32(const std::string& s, std::size_t at) {
    auto b = [&](std::size_t i) { return std::uint32_t(static_cast<unsigned char>(s[at + i])); };
    return b(0) << 24 | b(1) << 16 | b(2) << 8 | b(3);
}

struct PngChunk {
    std::string type;
    std::string data;
};

// The chunks of a PNG file, each CRC checked.
std::vector<PngChunk> pngChunks(const std::string& png) {
    std::vector<PngChunk> chunks;
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    for (std::size_t at = 8; at + 12 <= png.size();) {
        std::uint32_t length = readU32(png, at);
        EXPECT_LE(at + 12 + length, png.size());
        PngChunk c{png.substr(at + 4, 4), png.substr(at + 8, length)};
        auto crc = std::uint32_t(crc32(0L, reinterpret_cast<const Bytef*>(png.data() + at + 4), uInt(4 + length)));
        EXPECT_EQ(crc, readU32(png, at + 8 + length)) << c.type << " chunk at byte " << at;
        chunks.push_back(c);
        at += 12 + length;
    }
    return chunks;
}

// The scan lines of a PNG's IDAT chunks, inflated by zlib (which checks the stream's Adler-32).
std::string inflatedRows(const std::vector<PngChunk>& chunks, std::size_t expected) {
    std::string stream;
    for (const PngChunk& c : chunks) {
        if (c.type == "IDAT") {
            stream += c.data;
        }
    }
    std::string rows(expected + 1, '\0');
    uLongf size = uLongf(rows.size());
    EXPECT_EQ(uncompress(reinterpret_cast<Bytef*>(rows.data()), &size, reinterpret_cast<const Bytef*>(stream.data()),
                         uLong(stream.size())),
              Z_OK);
    rows.resize(size);
    return rows;
}

// Radiance over several decades, zeros, negatives and values far above white, in every channel.
Image testImage(std::uint32_t width, std::uint32_t height, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> exponent(-12.0f, 6.0f);
    std::uniform_int_distribution<int> kind(0, 9);
    Image image(width, height);
    for (glm::vec4& p : image.pixels) {
        for (int k = 0; k < 3; ++k) {
            int what = kind(rng);
            p[k] = what == 0 ? 0.0f : what == 1 ? -std::exp2(exponent(rng)) : std::exp2(exponent(rng));
        }
    }
    return image;
}

class ImageFiles : public test::TempFolderTest {
protected:
    ImageFiles() : TempFolderTest("photon-image-files-") {}
};

TEST(ImageSrgb8, TableEqualsTheFormula) {
    auto exact = [](float x) { return int(std::lround(srgbEncode(x) * 255.0f)); };
    // Around every code's first value (the table's thresholds) and every bucket's first float.
    for (std::uint32_t bits = 0; bits <= 0x3F800000u; bits += 1u << 16) {
        for (std::int32_t d = -2; d <= 2; ++d) {
            std::uint32_t b = std::uint32_t(std::int64_t(bits) + d);
            float x;
            std::memcpy(&x, &b, sizeof x);
            if (b <= 0x3F800000u) {
                ASSERT_EQ(int(srgb8(x)), exact(x)) << "x = " << x;
            }
        }
    }
    for (int v = 0; v <= 255; ++v) {
        float x = v / 255.0f;
        // The value whose encoding is v/255 and its neighbours: where the rounding changes.
        float inverse = x <= 0.04045f ? x / 12.92f : std::pow((x + 0.055f) / 1.055f, 2.4f);
        for (float y : {inverse, std::nextafter(inverse, 0.0f), std::nextafter(inverse, 1.0f), x}) {
            ASSERT_EQ(int(srgb8(y)), exact(y)) << "x = " << y;
        }
    }
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 2000000; ++i) {
        float x = unit(rng);
        ASSERT_EQ(int(srgb8(x)), exact(x)) << "x = " << x;
    }
    EXPECT_EQ(srgb8(-1.0f), 0);
    EXPECT_EQ(srgb8(-0.0f), 0);
    EXPECT_EQ(srgb8(std::numeric_limits<float>::denorm_min()), 0);
    EXPECT_EQ(srgb8(1.0f), 255);
    EXPECT_EQ(srgb8(7.5f), 255);
    EXPECT_EQ(srgb8(INFINITY), 255);
    EXPECT_EQ(srgb8(NAN), 0);
}

// Sizes below, at and across the 32-row bands, one pixel, a single row and a single column.
TEST_F(ImageFiles, PngDecodesToTheToneMappedBytes) {
    struct Case {
        std::uint32_t width, height;
        float exposure;
        Tonemap curve;
    };
    for (Case c : {Case{97, 61, 0.0f, Tonemap::Aces}, Case{1, 1, 0.0f, Tonemap::Aces},
                   Case{33, 32, 2.0f, Tonemap::Clamp}, Case{5, 160, -1.5f, Tonemap::Reinhard},
                   Case{640, 1, 0.0f, Tonemap::Aces}, Case{1, 70, 0.0f, Tonemap::Clamp}}) {
        SCOPED_TRACE(std::to_string(c.width) + "x" + std::to_string(c.height));
        Image image = testImage(c.width, c.height, c.width * 1000 + c.height);
        std::string file = path("t.png");
        writeImage(file, image, c.exposure, c.curve);
        std::string png = test::fileBytes(file);

        std::vector<PngChunk> chunks = pngChunks(png);
        ASSERT_GE(chunks.size(), 6u);
        EXPECT_EQ(chunks.front().type, "IHDR");
        EXPECT_EQ(chunks.back().type, "IEND");
        std::size_t raw = (1 + std::size_t(c.width) * 3) * c.height;
        std::string rows = inflatedRows(chunks, raw);
        ASSERT_EQ(rows.size(), raw);

        int w = 0;
        int h = 0;
        int n = 0;
        unsigned char* decoded = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()), int(png.size()),
                                                       &w, &h, &n, 3);
        ASSERT_NE(decoded, nullptr) << stbi_failure_reason();
        ASSERT_EQ(w, int(c.width));
        ASSERT_EQ(h, int(c.height));
        EXPECT_EQ(n, 3);
        float scale = std::exp2(c.exposure);
        int wrong = 0;
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
            glm::vec3 t = tonemap(glm::vec3(image.pixels[i]), scale, static_cast<std::uint32_t>(c.curve));
            for (int k = 0; k < 3; ++k) {
                wrong += decoded[3 * i + k] != static_cast<unsigned char>(std::lround(t[k] * 255.0f));
            }
        }
        stbi_image_free(decoded);
        EXPECT_EQ(wrong, 0);
    }
}

TEST_F(ImageFiles, PngCarriesSrgbBeforeItsPixels) {
    std::string file = path("srgb.png");
    writeImage(file, testImage(40, 40, 3), 0.0f, Tonemap::Aces);
    std::vector<PngChunk> chunks = pngChunks(test::fileBytes(file));
    std::map<std::string, std::size_t> first;
    for (std::size_t i = 0; i < chunks.size(); ++i) {
        first.emplace(chunks[i].type, i);
    }
    ASSERT_TRUE(first.count("sRGB"));
    ASSERT_TRUE(first.count("IDAT"));
    EXPECT_LT(first["sRGB"], first["IDAT"]);
    EXPECT_EQ(chunks[first["sRGB"]].data, std::string(1, '\0'));  // perceptual rendering intent
    ASSERT_TRUE(first.count("gAMA"));
    EXPECT_LT(first["gAMA"], first["IDAT"]);
    EXPECT_EQ(readU32(chunks[first["gAMA"]].data, 0), 45455u);
    ASSERT_TRUE(first.count("cHRM"));
    EXPECT_EQ(chunks[first["cHRM"]].data.size(), 32u);
    const std::string& header = chunks[0].data;
    EXPECT_EQ(readU32(header, 0), 40u);
    EXPECT_EQ(readU32(header, 4), 40u);
    EXPECT_EQ(header.substr(8), std::string("\x08\x02\x00\x00\x00", 5));  // 8-bit RGB, not interlaced
}

TEST_F(ImageFiles, Rgb8PngDecodesToItsBytes) {
    std::uint32_t width = 123;
    std::uint32_t height = 77;
    std::vector<unsigned char> rgb(std::size_t(width) * height * 3);
    std::mt19937 rng(11);
    for (unsigned char& b : rgb) {
        b = static_cast<unsigned char>(rng());
    }
    std::string file = path("rgb.png");
    writeRgb8Png(file, rgb.data(), width, height);
    std::string png = test::fileBytes(file);
    inflatedRows(pngChunks(png), (1 + std::size_t(width) * 3) * height);
    int w = 0;
    int h = 0;
    int n = 0;
    unsigned char* decoded =
        stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()), int(png.size()), &w, &h, &n, 3);
    ASSERT_NE(decoded, nullptr) << stbi_failure_reason();
    ASSERT_EQ(w, int(width));
    ASSERT_EQ(h, int(height));
    EXPECT_EQ(std::memcmp(decoded, rgb.data(), rgb.size()), 0);
    stbi_image_free(decoded);
}

// The same rows always give the same file, however many threads encode it.
TEST_F(ImageFiles, PngBytesRepeat) {
    Image image = testImage(300, 200, 5);
    EXPECT_EQ(encodeImage(ImageFormat::Png, image, 0.0f, Tonemap::Aces),
              encodeImage(ImageFormat::Png, image, 0.0f, Tonemap::Aces));
}

TEST_F(ImageFiles, ExrReadsBackFloatForFloat) {
    Image image = testImage(129, 67, 9);
    using limits = std::numeric_limits<float>;
    image.at(0, 0) = glm::vec4(limits::max(), limits::denorm_min(), -0.0f, 1.0f);
    auto expectSame = [&](const Image& back) {
        ASSERT_EQ(back.width, image.width);
        ASSERT_EQ(back.height, image.height);
        int wrong = 0;
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
            for (int k = 0; k < 3; ++k) {
                wrong += std::memcmp(&back.pixels[i][k], &image.pixels[i][k], sizeof(float)) != 0;
            }
        }
        EXPECT_EQ(wrong, 0);
    };
    // Through writeImage (the default compression), then each compression the writer offers.
    writeImage(path("t.exr"), image, 0.0f, Tonemap::Aces);
    expectSame(readImage(path("t.exr")));
    for (ExrLayout l : {ExrLayout::Tiles, ExrLayout::Scanlines}) {
        for (ExrCompression c : {ExrCompression::None, ExrCompression::Rle, ExrCompression::Zips, ExrCompression::Zip,
                                 ExrCompression::Piz}) {
            SCOPED_TRACE(std::string(toString(c)) + ", " + toString(l));
            std::string file = path("t.exr");
            writeOutputFile(file, encodeExr(image, c, l), "image");
            expectSame(readImage(file));
        }
    }
    // One pixel, one row, one column, tiles cut by both edges.
    for (auto [w, h] : {std::pair{1u, 1u}, std::pair{200u, 1u}, std::pair{1u, 40u}, std::pair{300u, 130u}}) {
        image = testImage(w, h, w + h);
        writeImage(path("small.exr"), image, 0.0f, Tonemap::Aces);
        expectSame(readImage(path("small.exr")));
    }
}

// An EXR file Photon writes can light a scene: the environment loader, which reads scan-line files
// only, takes it texel for texel.
TEST_F(ImageFiles, ExrServesAsAnEnvironmentMap) {
    Image image = testImage(64, 32, 17);
    for (glm::vec4& p : image.pixels) {
        p = glm::abs(p);
    }
    writeImage(path("env.exr"), image, 0.0f, Tonemap::Aces);
    EnvironmentMap map = loadEnvironmentMap(path("env.exr"));
    ASSERT_EQ(map.width, image.width);
    ASSERT_EQ(map.height, image.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        ASSERT_EQ(map.texels[i], glm::vec3(image.pixels[i])) << "texel " << i;
    }
}

TEST_F(ImageFiles, PfmReadsBackFloatForFloat) {
    Image image = testImage(31, 17, 13);
    writeImage(path("t.pfm"), image, 0.0f, Tonemap::Aces);
    Image back = readImage(path("t.pfm"));
    ASSERT_EQ(back.pixels.size(), image.pixels.size());
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        EXPECT_EQ(glm::vec3(back.pixels[i]), glm::vec3(image.pixels[i]));
    }
}

}  // namespace
}  // namespace photon
