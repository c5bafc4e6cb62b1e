// photon-make-smoke-vdb: writes the procedural smoke plume (smoke_field.h) as an OpenVDB file, the
// way Houdini and Blender write smoke: a FloatGrid named "density" of class fog volume, whose
// voxels below 1e-3 are left inactive (the background, 0), pruned, Blosc-compressed, with grid
// offsets (as openvdb::io::File writes them). Its transform puts the plume in its box,
// (-0.5, 0, -0.5) … (0.5, 2, 0.5). Made this way:
//   photon-make-smoke-vdb scenes/smoke.vdb --resolution 64
//   photon-make-smoke-vdb tests/fuzz/corpus/vdb_loader_fuzz/plume.vdb --resolution 6
#include <cstdio>
#include <sstream>

#include <CLI/CLI.hpp>
#include <openvdb/io/Archive.h>
#include <openvdb/openvdb.h>

#include "core/system/error.h"
#include "core/system/output_file.h"
#include "core/system/program.h"
#include "tools/smoke_field.h"

namespace photon {
namespace {

// Voxels below this are left inactive: the background (0) stands for them, and the file keeps
// only the leaves (8³ voxels) that hold smoke.
constexpr float kActiveMin = 1e-3f;

// OpenVDB writes grid offsets (with which a reader can go straight to one grid) only through
// io::File, to a file it names itself; this exposes the same writer for a stream in memory, so
// that the bytes go through writeOutputFile (whole or not at all).
struct SeekableArchive : openvdb::io::Archive {
    std::string bytes(const openvdb::GridCPtrVec& grids) const {
        std::ostringstream out(std::ios::binary);
        write(out, grids, /*seekable=*/true);
        return out.str();
    }
};

int run(int argc, char** argv) {
    CLI::App app{"Writes the procedural smoke plume as an OpenVDB file (a FloatGrid named density)", "photon-make-smoke-vdb"};
    std::string output;
    std::uint32_t resolution = 64;
    std::uint32_t seed = 2;
    app.add_option("output", output, "The .vdb file")->required()->check(kFileName);
    app.add_option("--resolution", resolution, "Voxels across (x and z); the plume is twice as many tall (y)")
        ->check(CLI::Range(1u, kDensityResolutionMax / 2));
    app.add_option("--seed", seed, "The seed of the plume's noise");
    if (int code = parseCommandLine(app, argc, argv); code >= 0) {
        return code;
    }
    if (output.size() < 4 || output.compare(output.size() - 4, 4, ".vdb") != 0) {
        throw InputError(output + ": an OpenVDB file's name ends in .vdb (scene files name grids by it)");
    }
    checkOutputPath(output, "OpenVDB file");
    glm::uvec3 size(resolution, 2 * resolution, resolution);
    DensityGrid plume = tools::makeSmokePlume(size, seed);

    openvdb::initialize();
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(/*background=*/0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    // Voxel (i, j, k) is centred on index point (i, j, k) in OpenVDB, so on lower + (i + ½) · size.
    const double voxel = double(plume.upper.y - plume.lower.y) / size.y;
    openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform(voxel);
    transform->postTranslate(openvdb::Vec3d(plume.lower.x, plume.lower.y, plume.lower.z) + 0.5 * voxel);
    grid->setTransform(transform);
    openvdb::FloatGrid::Accessor voxels = grid->getAccessor();
    std::size_t active = 0;
    for (std::uint32_t z = 0; z < size.z; ++z) {
        for (std::uint32_t y = 0; y < size.y; ++y) {
            for (std::uint32_t x = 0; x < size.x; ++x) {
                if (float d = plume.at(x, y, z); d >= kActiveMin) {
                    voxels.setValue(openvdb::Coord(int(x), int(y), int(z)), d);
                    ++active;
                }
            }
        }
    }
    grid->pruneGrid(0.0f);  // nodes of one value become tiles (none here but empty ones)

    SeekableArchive archive;
    archive.setCompression(openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
    std::string bytes = archive.bytes({grid});
    writeOutputFile(output, bytes, "OpenVDB file");
    std::fprintf(stderr, "photon-make-smoke-vdb: %ux%ux%u voxels, %zu active in %zu leaves -> %s, %zu bytes\n", size.x, size.y,
                 size.z, active, std::size_t(grid->tree().leafCount()), output.c_str(), bytes.size());
    return 0;
}

}  // namespace
}  // namespace photon

int main(int argc, char** argv) {
    return photon::runProgram("photon-make-smoke-vdb", [&] { return photon::run(argc, argv); });
}
