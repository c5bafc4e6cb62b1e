// Environment map loader tests: Radiance HDR and OpenEXR files written here (stb_image_write,
// tinyexr) load back texel for texel with row 0 at the top, and every bad file (missing, empty,
// truncated, corrupt, another format, too large, non-finite or negative texels) is one
// InputError that names it, the too-large ones without decoding a pixel.
#include "core/loaders/environment_loader.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "core/image/image.h"
#include "core/system/error.h"
#include "temp_folder.h"
#include "tools/environment_files.h"

namespace photon {
namespace {

namespace fs = std::filesystem;
using tools::ExrCompression;
using tools::ExrType;
using tools::exrAttribute;
using tools::exrBytes;
using tools::exrChunk;

// A texel that tells its place: its channels differ from each other and from every other texel's.
glm::vec3 probe(int x, int y) { return glm::vec3(1.0f + 0.25f * x, 1.5f + 0.125f * y, 1.25f) * float(1 + x + 7 * y); }

std::vector<glm::vec3> probeTexels(int width, int height) {
    std::vector<glm::vec3> texels;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            texels.push_back(probe(x, y));
        }
    }
    return texels;
}

// Files in a folder of the test's own, removed afterwards.
class EnvironmentLoader : public test::TempFolderTest {
protected:
    EnvironmentLoader() : TempFolderTest("photon-environment-") {}

    std::string write(const std::string& name, const std::string& bytes) const {
        std::ofstream(path(name), std::ios::binary) << bytes;
        return path(name);
    }

    std::string hdr(const std::string& name, int width, int height, const std::vector<glm::vec3>& texels) const {
        return write(name, tools::hdrBytes(width, height, texels));
    }

    // The message of the InputError that loading `file` raises; "(loaded)" if none.
    static std::string errorOf(const std::string& file) {
        try {
            loadEnvironmentMap(file);
        } catch (const InputError& e) {
            return e.what();
        }
        return "(loaded)";
    }

    // Expects one line "<file>: ...<reason>...".
    static void expectError(const std::string& file, const std::string& reason) {
        std::string message = errorOf(file);
        EXPECT_EQ(message.rfind(file + ": ", 0), 0u) << message;
        EXPECT_NE(message.find(reason), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
};

void putInt32(std::string& bytes, std::size_t at, std::int32_t value) { std::memcpy(&bytes[at], &value, 4); }

void expectTexels(const EnvironmentMap& map, int width, int height, const std::vector<glm::vec3>& expected, float tolerance) {
    ASSERT_EQ(map.width, std::uint32_t(width));
    ASSERT_EQ(map.height, std::uint32_t(height));
    ASSERT_EQ(map.texels.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        glm::vec3 want = expected[i];
        float scale = std::max(want.x, std::max(want.y, want.z));
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(map.texels[i][k], want[k], tolerance * scale)
                << "texel (" << i % std::size_t(width) << ", " << i / std::size_t(width) << ") channel " << k;
        }
    }
}

// ---- Radiance HDR --------------------------------------------------------------------------------

// Widths 8 to 32767 are run-length encoded by stb_image_write, others flat; both keep row 0 on top.
// RGBE keeps 8 bits a channel under the exponent of the texel's largest: within 1% of that one.
TEST_F(EnvironmentLoader, HdrRoundTripsTopRowFirst) {
    for (int width : {1, 5, 64}) {
        int height = width == 1 ? 1 : 9;
        std::vector<glm::vec3> texels = probeTexels(width, height);
        std::string file = hdr("probe-" + std::to_string(width) + ".hdr", width, height, texels);
        SCOPED_TRACE(file);
        expectTexels(loadEnvironmentMap(file), width, height, texels, 0.01f);
    }
}

TEST_F(EnvironmentLoader, ZeroMapIsValid) {
    std::vector<glm::vec3> black(16 * 8, glm::vec3(0.0f));
    expectTexels(loadEnvironmentMap(hdr("black.hdr", 16, 8, black)), 16, 8, black, 0.0f);
    expectTexels(loadEnvironmentMap(write("black.exr", exrBytes(16, 8, black))), 16, 8, black, 0.0f);
}

// Cut in half: stb_image by itself never returns from the run-length one (past the end it reads
// zeros, and a dump of zero texels never ends the scanline).
TEST_F(EnvironmentLoader, TruncatedHdrIsRefused) {
    for (int width : {5, 64}) {  // flat, run-length encoded
        std::string whole = test::fileBytes(hdr("whole.hdr", width, 32, probeTexels(width, 32)));
        std::string file = write("half-" + std::to_string(width) + ".hdr", whole.substr(0, whole.size() / 2));
        expectError(file, "truncated HDR file: the pixels stop in row");
        // Cut inside the header, and just before the last byte of the pixels.
        expectError(write("header.hdr", whole.substr(0, 30)), "truncated HDR file: it ends in its header");
        expectError(write("short.hdr", whole.substr(0, whole.size() - 1)), "truncated HDR file");
    }
}

TEST_F(EnvironmentLoader, CorruptHdrIsRefused) {
    std::string bytes = test::fileBytes(hdr("whole.hdr", 64, 4, probeTexels(64, 4)));
    std::size_t pixels = bytes.find("+X 64\n") + 6;
    std::string wide = bytes;
    wide[pixels + 3] = char(65);  // the first scanline says 65 texels
    expectError(write("wide.hdr", wide), "corrupt HDR file: row 0 says it holds 65 texels, not 64");
    std::string run = bytes;
    run[pixels + 4] = char(128 + 127);  // a run of 127 in a row of 64
    expectError(write("run.hdr", run), "corrupt HDR file: a run-length code overflows row 0");
}

// A header that claims 65536 × 32768 texels fails at once: nothing of the 24 GiB it would decode
// to is allocated (a decoder that tried would take seconds, or be killed).
TEST_F(EnvironmentLoader, HugeHdrFailsFast) {
    auto start = std::chrono::steady_clock::now();
    std::string file = write("huge.hdr", std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 32768 +X 65536\n") + "\x02\x02\x01\x00ab");
    expectError(file, "a map of 65536x32768 texels; environment maps are 1x1 to 16384x8192");
    expectError(write("wide.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 16385\n"), "a map of 16385x1 texels");
    expectError(write("empty.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 4\n"), "a map of 4x0 texels");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}

// ---- OpenEXR -------------------------------------------------------------------------------------

// 32-bit floats come back exactly, RGB or RGBA (alpha ignored), whatever the compression: 40 rows
// are 40 chunks uncompressed, 3 of ZIP's 16 lines and 2 of PIZ's 32.
TEST_F(EnvironmentLoader, ExrRoundTripsTopRowFirst) {
    std::vector<glm::vec3> texels = probeTexels(5, 40);
    for (std::string channels : {"RGB", "RGBA"}) {
        for (ExrCompression compression :
             {ExrCompression::None, ExrCompression::Rle, ExrCompression::Zips, ExrCompression::Zip, ExrCompression::Piz}) {
            std::string file = write(channels + std::to_string(int(compression)) + ".exr",
                                     exrBytes(5, 40, texels, channels, ExrType::Float, compression));
            SCOPED_TRACE(file);
            expectTexels(loadEnvironmentMap(file), 5, 40, texels, 0.0f);
        }
    }
    std::vector<glm::vec3> one{glm::vec3(2.0f, 0.0f, 0.5f)};
    expectTexels(loadEnvironmentMap(write("one.exr", exrBytes(1, 1, one))), 1, 1, one, 0.0f);
}

// Half floats: 11 significant bits, within 0.1%.
TEST_F(EnvironmentLoader, HalfExr) {
    std::vector<glm::vec3> texels = probeTexels(7, 3);
    std::string file = write("half.exr", exrBytes(7, 3, texels, "RGBA", ExrType::Half));
    expectTexels(loadEnvironmentMap(file), 7, 3, texels, 1e-3f);
}

// lineOrder DECREASING_Y only says the chunks lie in the file bottom up; the image is the same
// (tinyexr by itself would turn it upside down).
TEST_F(EnvironmentLoader, DecreasingLineOrderKeepsTheTopOnTop) {
    std::vector<glm::vec3> texels = probeTexels(6, 20);
    std::string bytes = exrBytes(6, 20, texels, "RGB", ExrType::Float, ExrCompression::None);
    bytes[exrAttribute(bytes, "lineOrder", "lineOrder")] = 1;
    expectTexels(loadEnvironmentMap(write("decreasing.exr", bytes)), 6, 20, texels, 0.0f);
}

TEST_F(EnvironmentLoader, BadTexelsAreRefused) {
    std::vector<glm::vec3> texels = probeTexels(4, 3);
    texels[1 * 4 + 2].y = std::numeric_limits<float>::quiet_NaN();
    expectError(write("nan.exr", exrBytes(4, 3, texels)), "texel (2, 1) is not finite");
    texels[1 * 4 + 2].y = std::numeric_limits<float>::infinity();
    expectError(write("inf.exr", exrBytes(4, 3, texels, "RGB", ExrType::Half)), "texel (2, 1) is not finite");
    texels[1 * 4 + 2].y = 1.0f;
    texels[2 * 4 + 3].z = -0.5f;
    texels[2 * 4 + 1].x = -1.0f;  // the first one is named
    expectError(write("negative.exr", exrBytes(4, 3, texels)),
                "texel (1, 2) is negative (-1, 28, 20): radiance cannot be negative");
}

TEST_F(EnvironmentLoader, TruncatedExrIsRefused) {
    std::string whole = exrBytes(64, 64, probeTexels(64, 64));
    expectError(write("half.exr", whole.substr(0, whole.size() / 2)), "truncated EXR file: chunk 2 of 4");
    expectError(write("short.exr", whole.substr(0, whole.size() - 1)), "truncated EXR file: chunk 3 of 4 ends beyond");
    expectError(write("table.exr", whole.substr(0, exrChunk(whole, 0) - 10)), "truncated EXR file: it ends in its offset table");
    expectError(write("header.exr", whole.substr(0, 100)), "cannot read the EXR header");
    expectError(write("version.exr", whole.substr(0, 6)), "not an OpenEXR file tinyexr reads");
}

// A chunk that holds other lines than its place says would leave lines undecoded.
TEST_F(EnvironmentLoader, CorruptExrChunkIsRefused) {
    std::string bytes = exrBytes(3, 8, probeTexels(3, 8), "RGB", ExrType::Float, ExrCompression::None);
    putInt32(bytes, exrChunk(bytes, 5), 4);
    expectError(write("repeated.exr", bytes), "corrupt EXR file: chunk 5 of 8 holds line 4, not 5");
}

TEST_F(EnvironmentLoader, ExrWithoutColourIsRefused) {
    std::string file = write("rg.exr", exrBytes(2, 2, probeTexels(2, 2), "RGA"));
    expectError(file, "the EXR file has no B channel of half or 32-bit floats");
}

TEST_F(EnvironmentLoader, HugeExrFailsFast) {
    auto start = std::chrono::steady_clock::now();
    std::string bytes = exrBytes(4, 4, probeTexels(4, 4));
    std::size_t window = exrAttribute(bytes, "dataWindow", "box2i");
    putInt32(bytes, window + 8, 65535);
    putInt32(bytes, window + 12, 32767);
    expectError(write("huge.exr", bytes), "a map of 65536x32768 texels");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}

// ---- Any file ------------------------------------------------------------------------------------

TEST_F(EnvironmentLoader, FilesThatAreNoMapAreRefused) {
    expectError(path("missing.hdr"), "cannot open environment map: No such file or directory");
    expectError(write("empty.exr", ""), "empty file, not an environment map");
    const unsigned char rgb[6] = {255, 128, 0, 0, 0, 255};
    writeRgb8Png(path("sky.png"), rgb, 2, 1);
    expectError(path("sky.png"), "neither a Radiance HDR nor an OpenEXR image (by its first bytes), though its name ends in '.png'");
    expectError(write("sky", "P6\n1 1\n255\nabc"), "though its name has no extension");
    expectError(write("format.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\nabcd"), "a Radiance header stb_image does not read");
    expectError(folder.string(), "a directory, not an environment map");
}

// The fuzz target's seeds (photon-make-environment-corpus) are maps the loader reads, so that the
// fuzzer starts from inside every decoder; the one of lineOrder DECREASING_Y is its twin's image.
TEST_F(EnvironmentLoader, FuzzSeedsLoad) {
    fs::path seeds = fs::path(PHOTON_SOURCE_DIR) / "tests/fuzz/corpus/environment_loader_fuzz";
    int count = 0;
    for (const fs::directory_entry& seed : fs::directory_iterator(seeds)) {
        EXPECT_NO_THROW(loadEnvironmentMap(seed.path().string())) << seed.path();
        count += 1;
    }
    EXPECT_GE(count, 9);
    EnvironmentMap decreasing = loadEnvironmentMap((seeds / "decreasing.exr").string());
    expectTexels(decreasing, 3, 2, loadEnvironmentMap((seeds / "none.exr").string()).texels, 0.0f);
}

// Inputs the fuzzer once crashed a decoder with are bad maps: each is one InputError naming it.
TEST_F(EnvironmentLoader, FuzzFindingsAreRefusedByName) {
    fs::path findings = fs::path(PHOTON_SOURCE_DIR) / "tests/fuzz/findings/environment_loader_fuzz";
    int count = 0;
    for (const fs::directory_entry& finding : fs::directory_iterator(findings)) {
        expectError(finding.path().string(), "");
        count += 1;
    }
    EXPECT_GE(count, 1);
}

}  // namespace
}  // namespace photon
