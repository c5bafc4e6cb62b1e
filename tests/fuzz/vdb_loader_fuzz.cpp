// libFuzzer target for the OpenVDB loader: the input is the bytes of a .vdb file (seeded with the
// smoke plume photon-make-smoke-vdb writes), decoded as a scene's density grid is; odd lengths ask
// for the grid named "density", even ones for the file's first grid of floats. It must raise
// InputError, or give a grid of at most 32 voxels an axis, its box finite, every voxel finite and
// ≥ 0. Anything else (another exception, a crash, a sanitizer report, a leak, a hang) is a bug, in
// the loader or in the OpenVDB reader it guards (libopenvdb itself is not instrumented, but its
// templates, which read the trees, are compiled into the loader).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/loaders/vdb_loader.h"
#include "core/system/error.h"

namespace {

constexpr std::uint32_t kMaxResolution = 32;

bool valid(const photon::DensityGrid& grid) {
    glm::uvec3 r = grid.resolution;
    if (r.x < 1 || r.y < 1 || r.z < 1 || r.x > kMaxResolution || r.y > kMaxResolution || r.z > kMaxResolution ||
        grid.density.size() != std::size_t(r.x) * r.y * r.z) {
        return false;
    }
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(grid.lower[a]) || !std::isfinite(grid.upper[a]) || !(grid.lower[a] < grid.upper[a])) {
            return false;
        }
    }
    for (float d : grid.density) {
        if (!std::isfinite(d) || d < 0.0f) {
            return false;
        }
    }
    return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        photon::DensityGrid grid = photon::decodeVdbDensity(bytes, "input.vdb", size % 2 ? "density" : "", kMaxResolution);
        if (!valid(grid)) {
            std::fprintf(stderr, "a grid of %ux%ux%u voxels (%zu values) that breaks the loader's promises\n", grid.resolution.x,
                         grid.resolution.y, grid.resolution.z, grid.density.size());
            std::abort();
        }
    } catch (const photon::InputError& e) {
        // Rejected input: the expected outcome for most mutations.
        if (std::getenv("PHOTON_FUZZ_TRACE")) {
            std::fprintf(stderr, "refused: %s\n", e.what());
        }
    }
    return 0;
}
