// OpenVDB loader tests: grids written here by OpenVDB itself (io::File with grid offsets, io::Stream
// without) load back voxel for voxel with their box, in every compression and as half floats;
// averaged down they keep the integral of density; a grid is picked by name; and every bad file
// (missing grid, wrong type, negative or non-finite voxel, truncated anywhere, chunk sizes that
// OpenVDB would overflow a buffer with, another format version, too large a tree, not a VDB file,
// rotated, frustum or mirrored transform, empty grid) is one InputError that names it. The smoke
// plume written by photon-make-smoke-vdb loads back as makeSmokePlume makes it.
#include "core/loaders/vdb_loader.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>

#include "core/loaders/vdb_layout.h"
#include "core/system/error.h"
#include "temp_folder.h"
#include "tools/smoke_field.h"

namespace photon {
namespace {

using openvdb::Coord;

// Files in a folder of the test's own, removed afterwards.
class VdbLoader : public test::TempFolderTest {
protected:
    VdbLoader() : TempFolderTest("photon-vdb-") { openvdb::initialize(); }

    // The grids as io::File writes them (grid offsets, Blosc unless told otherwise), or as
    // io::Stream does (no offsets: a reader must walk every grid before the one it wants).
    std::string writeVdb(const std::string& name, const openvdb::GridPtrVec& grids,
                         std::uint32_t compression = openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK,
                         bool offsets = true) const {
        if (offsets) {
            openvdb::io::File file(path(name));
            file.setCompression(compression);
            file.write(grids);
            file.close();
        } else {
            std::ofstream out(path(name), std::ios::binary);
            openvdb::io::Stream stream(out);
            stream.setCompression(compression);
            stream.write(grids);
        }
        return path(name);
    }

    std::string writeBytes(const std::string& name, const std::string& bytes) const {
        std::ofstream(path(name), std::ios::binary) << bytes;
        return path(name);
    }

    // The message of the InputError that loading `file` raises; "(loaded)" if none.
    static std::string errorOf(const std::string& file, const std::string& grid = "", std::uint32_t maxResolution = 64) {
        try {
            loadVdbDensity(file, grid, maxResolution);
        } catch (const InputError& e) {
            return e.what();
        }
        return "(loaded)";
    }

    // Expects one line "<file>: ...<reason>...".
    static void expectError(const std::string& file, const std::string& reason, const std::string& grid = "",
                            std::uint32_t maxResolution = 64) {
        std::string message = errorOf(file, grid, maxResolution);
        EXPECT_EQ(message.rfind(file + ": ", 0), 0u) << message;
        EXPECT_NE(message.find(reason), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
};

// A value that tells its voxel: distinct everywhere, exact in binary (and in half floats).
float probe(int x, int y, int z) { return 0.25f * float(1 + x + 5 * y + 15 * z); }

// A FloatGrid (or DoubleGrid) of nx × ny × nz probe voxels from index `origin`, placed by
// world = index · scale + translation.
template <typename GridT = openvdb::FloatGrid>
typename GridT::Ptr probeGrid(const std::string& name, Coord origin, Coord size, openvdb::Vec3d scale = openvdb::Vec3d(1.0),
                              openvdb::Vec3d translation = openvdb::Vec3d(0.0)) {
    typename GridT::Ptr grid = GridT::create(0);
    grid->setName(name);  // class unknown: a fog volume's grid is never Zip-compressed
    grid->setTransform(openvdb::math::Transform::Ptr(
        new openvdb::math::Transform(std::make_shared<openvdb::math::ScaleTranslateMap>(scale, translation))));
    auto voxels = grid->getAccessor();
    for (int z = 0; z < size.z(); ++z) {
        for (int y = 0; y < size.y(); ++y) {
            for (int x = 0; x < size.x(); ++x) {
                voxels.setValue(origin.offsetBy(x, y, z), probe(x, y, z));
            }
        }
    }
    return grid;
}

void expectProbe(const DensityGrid& grid, Coord size, float tolerance = 0.0f) {
    ASSERT_EQ(grid.resolution, glm::uvec3(size.x(), size.y(), size.z()));
    ASSERT_EQ(grid.density.size(), std::size_t(size.x()) * size.y() * size.z());
    for (int z = 0; z < size.z(); ++z) {
        for (int y = 0; y < size.y(); ++y) {
            for (int x = 0; x < size.x(); ++x) {
                EXPECT_NEAR(grid.at(x, y, z), probe(x, y, z), tolerance * probe(x, y, z)) << x << ", " << y << ", " << z;
            }
        }
    }
}

// ---- Loading -------------------------------------------------------------------------------------

// 5×3×2 voxels from index (-2, 3, 10), each 0.25 × 0.5 × 0.125 wide, translated by (1, -2, 0.5):
// the box is index (-2.5, 2.5, 9.5) … (2.5, 5.5, 11.5) through the map, every number exact.
TEST_F(VdbLoader, RoundTripsValuesAndBox) {
    const openvdb::Vec3d scale(0.25, 0.5, 0.125);
    const openvdb::Vec3d translation(1.0, -2.0, 0.5);
    const glm::vec3 lower(1.0f + 0.25f * -2.5f, -2.0f + 0.5f * 2.5f, 0.5f + 0.125f * 9.5f);
    const glm::vec3 upper(1.0f + 0.25f * 2.5f, -2.0f + 0.5f * 5.5f, 0.5f + 0.125f * 11.5f);
    const Coord size(5, 3, 2);
    for (bool offsets : {true, false}) {
        for (std::uint32_t compression : {0u, 1u, 2u, 3u, 4u, 6u}) {  // none, zip, active mask, both, blosc, blosc + mask
            std::string file = writeVdb("probe" + std::to_string(compression) + (offsets ? "" : "-stream") + ".vdb",
                                        {probeGrid("density", Coord(-2, 3, 10), size, scale, translation)}, compression, offsets);
            SCOPED_TRACE(file);
            DensityGrid grid = loadVdbDensity(file, "density", 64);
            expectProbe(grid, size);
            EXPECT_EQ(grid.lower, lower);
            EXPECT_EQ(grid.upper, upper);
        }
    }
}

TEST_F(VdbLoader, DoubleAndHalfFloatGrids) {
    const Coord size(5, 3, 2);
    std::string file = writeVdb("double.vdb", {probeGrid<openvdb::DoubleGrid>("density", Coord(0), size)});
    expectProbe(loadVdbDensity(file, "", 64), size);
    openvdb::FloatGrid::Ptr half = probeGrid("density", Coord(0), size);
    half->setSaveFloatAsHalf(true);
    expectProbe(loadVdbDensity(writeVdb("half.vdb", {half}), "density", 64), size, 1e-3f);
}

// The box of the active voxels, not of the grid's leaves or of the index origin; inactive voxels
// inside it take the background.
TEST_F(VdbLoader, BoxOfActiveVoxelsWithBackgroundBetween) {
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.5f);
    grid->setName("density");
    grid->tree().setValue(Coord(100, 7, -3), 2.0f);
    grid->tree().setValue(Coord(103, 7, -1), 3.0f);
    grid->tree().setValueOff(Coord(101, 7, -3), 9.0f);  // inactive: the background, not 9
    DensityGrid d = loadVdbDensity(writeVdb("sparse.vdb", {grid}), "", 64);
    ASSERT_EQ(d.resolution, glm::uvec3(4, 1, 3));
    EXPECT_EQ(d.at(0, 0, 0), 2.0f);
    EXPECT_EQ(d.at(3, 0, 2), 3.0f);
    EXPECT_EQ(d.at(1, 0, 0), 0.5f);
    EXPECT_EQ(d.at(2, 0, 1), 0.5f);
    EXPECT_EQ(d.lower, glm::vec3(99.5f, 6.5f, -3.5f));
    EXPECT_EQ(d.upper, glm::vec3(103.5f, 7.5f, -0.5f));
}

// An active tile (a node's worth of voxels of one value: 8³ … 4096³) counts voxel by voxel; its
// share of an averaged voxel by its overlap.
TEST_F(VdbLoader, ActiveTiles) {
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->tree().addTile(2, Coord(0), 2.0f, true);  // a tile of a level-2 node: 128³ voxels
    grid->tree().setValue(Coord(128, 0, 0), 4.0f);
    DensityGrid d = loadVdbDensity(writeVdb("tile.vdb", {grid}), "", 129);
    ASSERT_EQ(d.resolution, glm::uvec3(129, 128, 128));
    EXPECT_EQ(d.at(0, 0, 0), 2.0f);
    EXPECT_EQ(d.at(127, 127, 127), 2.0f);
    EXPECT_EQ(d.at(128, 0, 0), 4.0f);
    EXPECT_EQ(d.at(128, 1, 0), 0.0f);
    // Halved: 65 × 64 × 64 voxels of 2³; the last column holds one voxel of 4 among 8 (the rest
    // of its block lies past the box and counts the background, 0).
    DensityGrid half = loadVdbDensity(path("tile.vdb"), "", 65);
    ASSERT_EQ(half.resolution, glm::uvec3(65, 64, 64));
    EXPECT_FLOAT_EQ(half.at(10, 20, 30), 2.0f);
    EXPECT_FLOAT_EQ(half.at(64, 0, 0), 0.5f);
    EXPECT_EQ(half.upper, glm::vec3(129.5f, 127.5f, 127.5f));
}

// 40 × 17 × 9 voxels averaged into at most 8 along an axis: blocks of 5³ (ceil(40 / 8)), 8 × 4 × 2
// voxels, the last ones reaching past the grid (its background, 0, beyond). The sum of density
// times voxel volume is kept.
TEST_F(VdbLoader, DownsamplingKeepsTheIntegral) {
    const Coord size(40, 17, 9);
    const openvdb::Vec3d scale(0.1, 0.2, 0.3);
    openvdb::FloatGrid::Ptr grid = probeGrid("density", Coord(3, -4, 5), size, scale, openvdb::Vec3d(0.5, 0.0, -1.0));
    double integral = 0.0;
    for (auto v = grid->cbeginValueOn(); v; ++v) {
        integral += double(*v) * 0.1 * 0.2 * 0.3;
    }
    std::string file = writeVdb("wide.vdb", {grid});
    DensityGrid d = loadVdbDensity(file, "", 8);
    ASSERT_EQ(d.resolution, glm::uvec3(8, 4, 2));
    glm::dvec3 voxel = (glm::dvec3(d.upper) - glm::dvec3(d.lower)) / glm::dvec3(d.resolution);
    EXPECT_NEAR(voxel.x, 0.5, 1e-6);
    EXPECT_NEAR(voxel.y, 1.0, 1e-6);
    EXPECT_NEAR(voxel.z, 1.5, 1e-6);
    double sum = 0.0;
    for (float v : d.density) {
        sum += double(v) * voxel.x * voxel.y * voxel.z;
    }
    EXPECT_NEAR(sum, integral, 1e-5 * integral);
    // The first voxel is the mean of the first 5³ block.
    double block = 0.0;
    for (int z = 0; z < 5; ++z) {
        for (int y = 0; y < 5; ++y) {
            for (int x = 0; x < 5; ++x) {
                block += probe(x, y, z);
            }
        }
    }
    EXPECT_FLOAT_EQ(d.at(0, 0, 0), float(block / 125.0));
    EXPECT_FLOAT_EQ(d.lower.x, float(0.5 + 0.1 * 2.5));
    EXPECT_FLOAT_EQ(d.upper.x, float(0.5 + 0.1 * (2.5 + 40.0)));
}

// A grid by its name among two; no name: the first grid of floats.
TEST_F(VdbLoader, PicksTheNamedGrid) {
    openvdb::FloatGrid::Ptr temperature = probeGrid("temperature", Coord(0), Coord(2, 2, 2));
    openvdb::FloatGrid::Ptr density = probeGrid("density", Coord(0), Coord(3, 1, 1));
    for (bool offsets : {true, false}) {
        std::string file = writeVdb(offsets ? "two.vdb" : "two-stream.vdb", {temperature, density},
                                    openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK, offsets);
        EXPECT_EQ(loadVdbDensity(file, "density", 64).resolution, glm::uvec3(3, 1, 1));
        EXPECT_EQ(loadVdbDensity(file, "temperature", 64).resolution, glm::uvec3(2, 2, 2));
        EXPECT_EQ(loadVdbDensity(file, "", 64).resolution, glm::uvec3(2, 2, 2));
    }
}

// ---- Refused files -------------------------------------------------------------------------------

TEST_F(VdbLoader, MissingGridListsTheGrids) {
    openvdb::Vec3SGrid::Ptr velocity = openvdb::Vec3SGrid::create();
    velocity->setName("v");
    velocity->tree().setValue(Coord(0), openvdb::Vec3s(1.0f));
    std::string file = writeVdb("grids.vdb", {probeGrid("temperature", Coord(0), Coord(1, 1, 1)), velocity,
                                              probeGrid("density", Coord(0), Coord(1, 1, 1))});
    expectError(file, "no grid named 'smoke' in the file; its grids: 'temperature' (float), 'v' (vec3s), 'density' (float)",
                "smoke");
    expectError(file, "grid 'v' holds vec3s values; densities are grids of floats", "v");
    expectError(writeVdb("vectors.vdb", {velocity}),
                "no grid of floats (FloatGrid or DoubleGrid: OpenVDB's Tree_float_5_4_3 or Tree_double_5_4_3) in the file; its grids: 'v' (vec3s)");
}

// A float tree of another configuration (or a damaged type name) is not "float values" refused
// as not floats (issue 57).
TEST_F(VdbLoader, AnotherTreeConfigurationIsNamedAsSuch) {
    std::string file = writeVdb("config.vdb", {probeGrid("density", Coord(0), Coord(2, 2, 2))});
    std::string bytes;
    {
        std::ifstream in(file, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    for (std::size_t at = bytes.find("Tree_float_5_4_3"); at != std::string::npos; at = bytes.find("Tree_float_5_4_3", at)) {
        bytes.replace(at, 16, "Tree_float_5_4_4");
    }
    std::string patched = path("config-544.vdb");
    std::ofstream(patched, std::ios::binary) << bytes;
    for (const char* grid : {"density", ""}) {
        std::string message = errorOf(patched, grid, 64);
        EXPECT_EQ(message.find("holds float values"), std::string::npos) << message;
        EXPECT_NE(message.find("Tree_float_5_4_4"), std::string::npos) << message;
    }
    expectError(patched, "grid 'density' holds a tree of type 'Tree_float_5_4_4', not OpenVDB's standard", "density");
}

TEST_F(VdbLoader, NegativeOrNonFiniteVoxelsAreRefused) {
    openvdb::FloatGrid::Ptr grid = probeGrid("density", Coord(0), Coord(4, 4, 4));
    grid->tree().setValue(Coord(1, 2, 3), -0.5f);
    expectError(writeVdb("negative.vdb", {grid}),
                "grid 'density': voxel (1, 2, 3) is negative (-0.5); densities cannot be negative");
    grid->tree().setValue(Coord(1, 2, 3), std::numeric_limits<float>::quiet_NaN());
    expectError(writeVdb("nan.vdb", {grid}), "grid 'density': voxel (1, 2, 3) is not finite");
    grid->tree().setValue(Coord(1, 2, 3), std::numeric_limits<float>::infinity());
    expectError(writeVdb("infinite.vdb", {grid}), "voxel (1, 2, 3) is not finite");
    openvdb::DoubleGrid::Ptr big = probeGrid<openvdb::DoubleGrid>("density", Coord(0), Coord(2, 2, 2));
    big->tree().setValue(Coord(1, 1, 1), 1e300);  // finite, but not as a float
    expectError(writeVdb("double.vdb", {big}), "voxel (1, 1, 1) is not finite as a 32-bit float");
    // A negative background counts only where a voxel of the box is inactive.
    openvdb::FloatGrid::Ptr background = openvdb::FloatGrid::create(-1.0f);
    background->setName("density");
    background->tree().setValue(Coord(0), 1.0f);
    EXPECT_EQ(loadVdbDensity(writeVdb("full.vdb", {background}), "", 64).density, std::vector<float>{1.0f});
    background->tree().setValue(Coord(2, 0, 0), 1.0f);
    expectError(writeVdb("background.vdb", {background}), "its background (the value of inactive voxels) is negative (-1)");
}

TEST_F(VdbLoader, EmptyGridIsRefused) {
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    expectError(writeVdb("empty.vdb", {grid}), "grid 'density' has no active voxels (an empty grid)");
}

TEST_F(VdbLoader, TransformsOtherThanScaleAndTranslationAreRefused) {
    openvdb::FloatGrid::Ptr grid = probeGrid("density", Coord(0), Coord(2, 2, 2));
    openvdb::math::Transform::Ptr rotated = openvdb::math::Transform::createLinearTransform(0.5);
    rotated->postRotate(0.3, openvdb::math::Y_AXIS);
    grid->setTransform(rotated);
    expectError(writeVdb("rotated.vdb", {grid}), "grid 'density' is placed by a rotated or sheared AffineMap");
    grid->setTransform(openvdb::math::Transform::createFrustumTransform(openvdb::BBoxd(openvdb::Vec3d(0), openvdb::Vec3d(8)),
                                                                       0.5, 2.0, 0.25));
    expectError(writeVdb("frustum.vdb", {grid}), "grid 'density' is placed by a NonlinearFrustumMap (a frustum)");
    grid->setTransform(openvdb::math::Transform::Ptr(new openvdb::math::Transform(
        std::make_shared<openvdb::math::ScaleMap>(openvdb::Vec3d(1.0, -1.0, 1.0)))));
    expectError(writeVdb("mirrored.vdb", {grid}), "whose scale along y is -1 (a mirror)");
}

TEST_F(VdbLoader, NotVdbFilesAreRefused) {
    expectError(writeBytes("empty.vdb", ""), "an empty file; media's density grids are .vdb files");
    expectError(writeBytes("text.vdb", "density 1 2 3\n"), "not an OpenVDB file (by its first 8 bytes)");
    expectError(writeBytes("png.vdb", "\x89PNG\r\n\x1a\n0000"), "not an OpenVDB file");
    expectError(path("missing.vdb"), "missing.vdb");
}

// The message of decoding `bytes` as "cut.vdb"; "(loaded)" if none.
std::string decodeError(const std::string& bytes) {
    try {
        decodeVdbDensity(bytes, "cut.vdb", "", 64);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(loaded)";
}

// Cut anywhere, a file is refused with a message naming it. OpenVDB by itself reads on past the
// end of a stream: a string or chunk length it then reads is whatever its variable held, and
// allocating that many bytes ran for minutes.
TEST_F(VdbLoader, TruncatedFilesAreRefused) {
    for (bool offsets : {true, false}) {
        for (std::uint32_t compression : {0u, 1u, 6u}) {
            std::string whole = test::fileBytes(writeVdb("whole.vdb", {probeGrid("density", Coord(-5, 0, 0), Coord(10, 3, 2))},
                                                         compression, offsets));
            ASSERT_EQ(decodeError(whole), "(loaded)");
            // Every cut through the header and descriptor, then through the grid a few bytes apart.
            for (std::size_t length = 0; length < whole.size(); length += length < 600 ? 1 : 13) {
                std::string message = decodeError(whole.substr(0, length));
                ASSERT_EQ(message.rfind("cut.vdb: ", 0), 0u) << "cut at " << length << ": " << message;
            }
        }
    }
}

// The bytes of a file written by io::File of one voxel at (1, 2, 3) (its leaf's chunk last).
std::string oneVoxel(std::uint32_t compression) {
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->tree().setValue(Coord(1, 2, 3), 0.5f);
    std::ostringstream out;
    openvdb::io::Stream stream(out);
    stream.setCompression(compression);
    stream.write(openvdb::GridPtrVec{grid});
    return out.str();
}

// Chunk sizes OpenVDB trusts. Stored uncompressed (zlib does not shrink one float), the leaf's
// chunk says -4; saying -68 with 64 more bytes after it, OpenVDB 10 by itself copies 68 bytes into
// its 4-byte buffer (a heap overflow in io::unzipFromStream) before it compares the sizes. Blosc
// reads as far as its header's compressed size says, past the chunk. And a chunk that does not
// decompress makes OpenVDB throw from inside the node it was reading, which leaks.
TEST_F(VdbLoader, CorruptChunksAreRefused) {
    std::string zip = oneVoxel(openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK);
    ASSERT_EQ(decodeError(zip), "(loaded)");
    const std::int64_t minus4 = -4;
    ASSERT_EQ(zip.compare(zip.size() - 12, 8, reinterpret_cast<const char*>(&minus4), 8), 0);
    const std::int64_t minus68 = -68;
    std::string overflow = zip.substr(0, zip.size() - 12) + std::string(reinterpret_cast<const char*>(&minus68), 8) +
                           zip.substr(zip.size() - 4) + std::string(64, 'A');
    EXPECT_EQ(decodeError(overflow),
              "cut.vdb: corrupt VDB file: the tree of grid 'density': an uncompressed chunk of 68 bytes where 4 are due");

    std::string blosc = oneVoxel(openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
    ASSERT_EQ(decodeError(blosc), "(loaded)");
    std::int64_t size = 0;
    std::memcpy(&size, &blosc[blosc.size() - 28], 8);  // Blosc keeps one float in 20 bytes: its header, the float
    ASSERT_EQ(size, 20);
    // Blosc's flags say the float is stored as it is (memcpyed, 0x2): without, its 4 bytes are not
    // a compressed block (OpenVDB would throw, and leak the node it was reading).
    std::string flags = blosc;
    ASSERT_NE(flags[flags.size() - 20 + 2] & 0x2, 0);
    flags[flags.size() - 20 + 2] = char(flags[flags.size() - 20 + 2] & ~0x2);
    EXPECT_EQ(decodeError(flags),
              "cut.vdb: corrupt VDB file: the tree of grid 'density': a Blosc chunk that does not decompress to the 4 bytes due");
    const std::uint32_t beyond = 1000;
    std::memcpy(&blosc[blosc.size() - 20 + 12], &beyond, 4);  // the header's compressed size
    EXPECT_EQ(decodeError(blosc),
              "cut.vdb: corrupt VDB file: the tree of grid 'density': a Blosc chunk of 20 bytes whose header states 1000 "
              "bytes of 4 (4 are due)");
}

TEST_F(VdbLoader, FormatVersionsOutsideTheRangeAreRefused) {
    std::string bytes = oneVoxel(openvdb::io::COMPRESS_BLOSC);
    const std::uint32_t old = 221;
    std::memcpy(&bytes[8], &old, 4);
    EXPECT_EQ(decodeError(bytes), "cut.vdb: a VDB file of format version 221; Photon reads versions 222 to 224 (OpenVDB 3.0 "
                                  "and every later release)");
}

// A tree is refused before OpenVDB allocates it when it holds more values than the cap
// (kVdbTreeValuesMax, 2^30: here 1000, which the probe's one top node of 32³ slots passes).
TEST_F(VdbLoader, TooManyVoxelsAreRefusedBeforeReading) {
    std::string bytes = test::fileBytes(writeVdb("probe.vdb", {probeGrid("density", Coord(0), Coord(5, 3, 2))}));
    VdbLayout layout = readVdbLayout(bytes, "probe.vdb");
    ASSERT_EQ(layout.grids.size(), 1u);
    EXPECT_FALSE(vdbGridStream(bytes, layout, 0, "probe.vdb").empty());
    try {
        vdbGridStream(bytes, layout, 0, "probe.vdb", 1000);
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "probe.vdb: grid 'density' holds more than 1000 voxels and tiles in its tree, more than "
                               "Photon reads (average it down first)");
    }
}

// In a file without grid offsets (written by io::Stream) a grid is found by walking the ones
// before it; a grid of a type Photon cannot walk (bools) stops the walk. With offsets, it is
// stepped over.
TEST_F(VdbLoader, GridsOfOtherTypesBeforeTheDensity) {
    openvdb::BoolGrid::Ptr mask = openvdb::BoolGrid::create(false);
    mask->setName("mask");
    mask->tree().setValue(Coord(4, 4, 4), true);
    openvdb::Vec3SGrid::Ptr velocity = openvdb::Vec3SGrid::create();
    velocity->setName("v");
    velocity->tree().setValue(Coord(0), openvdb::Vec3s(1.0f));
    openvdb::FloatGrid::Ptr density = probeGrid("density", Coord(0), Coord(3, 1, 1));
    std::uint32_t blosc = openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK;
    EXPECT_EQ(loadVdbDensity(writeVdb("offsets.vdb", {mask, velocity, density}), "density", 64).resolution, glm::uvec3(3, 1, 1));
    EXPECT_EQ(loadVdbDensity(writeVdb("vectors.vdb", {velocity, density}, blosc, false), "density", 64).resolution,
              glm::uvec3(3, 1, 1));
    expectError(writeVdb("bools.vdb", {mask, density}, blosc, false),
                "no grid named 'density' in the file; its grids: 'mask' (bool) and whatever follows it in this file without grid "
                "offsets (written as a stream), which Photon cannot step over",
                "density");
}

TEST_F(VdbLoader, ResolutionOutsideItsRange) {
    std::string file = writeVdb("probe.vdb", {probeGrid("density", Coord(0), Coord(2, 2, 2))});
    expectError(file, "1 to 512 are possible", "", 0);
    expectError(file, "1 to 512 are possible", "", 513);
}

// ---- The smoke plume -----------------------------------------------------------------------------

// photon-make-smoke-vdb's file is the plume: its active voxels (>= 1e-3) as makeSmokePlume makes
// them, in its box; the voxels it left inactive come back as the background, 0.
TEST_F(VdbLoader, SmokePlumeRoundTrips) {
    const std::uint32_t n = 16;
    std::string file = path("plume.vdb");
    std::string command =
        std::string(PHOTON_MAKE_SMOKE_VDB) + " '" + file + "' --resolution " + std::to_string(n) + " --seed 5 2>/dev/null";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    std::string misnamed = std::string(PHOTON_MAKE_SMOKE_VDB) + " '" + path("plume.png") + "' --resolution 4 2>/dev/null";
    EXPECT_EQ(WEXITSTATUS(std::system(misnamed.c_str())), 2) << "a name that is no .vdb";
    EXPECT_FALSE(std::ifstream(path("plume.png")).good());
    DensityGrid plume = tools::makeSmokePlume(glm::uvec3(n, 2 * n, n), 5);
    // The box of the voxels of at least 1e-3.
    glm::uvec3 first(~0u);
    glm::uvec3 last(0u);
    for (std::uint32_t z = 0; z < n; ++z) {
        for (std::uint32_t y = 0; y < 2 * n; ++y) {
            for (std::uint32_t x = 0; x < n; ++x) {
                if (plume.at(x, y, z) >= 1e-3f) {
                    first = glm::min(first, glm::uvec3(x, y, z));
                    last = glm::max(last, glm::uvec3(x, y, z));
                }
            }
        }
    }
    DensityGrid d = loadVdbDensity(file, "density", 512);
    ASSERT_EQ(d.resolution, last - first + 1u);
    glm::vec3 voxel = (plume.upper - plume.lower) / glm::vec3(plume.resolution);
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(d.lower[a], plume.lower[a] + float(first[a]) * voxel[a], 1e-6f) << a;
        EXPECT_NEAR(d.upper[a], plume.lower[a] + float(last[a] + 1) * voxel[a], 1e-6f) << a;
    }
    for (std::uint32_t z = 0; z < d.resolution.z; ++z) {
        for (std::uint32_t y = 0; y < d.resolution.y; ++y) {
            for (std::uint32_t x = 0; x < d.resolution.x; ++x) {
                float want = plume.at(first.x + x, first.y + y, first.z + z);
                EXPECT_EQ(d.at(x, y, z), want >= 1e-3f ? want : 0.0f) << x << ", " << y << ", " << z;
            }
        }
    }
    // The committed scene file is the same plume at 64 × 128 × 64.
    DensityGrid scene = loadVdbDensity(std::string(PHOTON_SCENES_DIR) + "/smoke.vdb", "density", 512);
    EXPECT_LE(scene.resolution.x, 64u);
    EXPECT_LE(scene.resolution.y, 128u);
    EXPECT_GE(scene.lower.y, 0.0f);
    EXPECT_LE(scene.upper.y, 2.0f);
}

}  // namespace
}  // namespace photon
