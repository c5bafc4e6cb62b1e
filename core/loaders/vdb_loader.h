// Heterogeneous media from OpenVDB files: one scalar grid of a .vdb file (a FloatGrid or a
// DoubleGrid, the "density" of Houdini's and Blender's smoke) resampled into a dense DensityGrid.
// The grid's active voxels bound the box; a voxel keeps its value (the grid's background where it
// is inactive), and a grid wider than the resolution asked for is averaged down in f×f×f blocks,
// which keeps the integral of density (the medium's optical depth along any long path).
//
// The file's bytes are walked and checked (vdb_layout.h) before OpenVDB reads the one grid asked
// for. Only builds configured with PHOTON_OPENVDB=ON read the files (libopenvdb is 57 MB, and the
// GPU machine's build goes without it); the others throw InputError for every file.
#pragma once

#include <cstdint>
#include <string>

#include "core/scene/density_grid.h"

namespace photon {

// The cap on OpenVDB files: 2 GiB.
inline constexpr std::uint64_t kVdbFileLimit = std::uint64_t(2) << 30;

// The grid named `gridName` of the file at `path` (an empty name: its first FloatGrid, else its
// first DoubleGrid), at most `maxResolution` voxels along its longest axis (1 …
// kDensityResolutionMax). Throws InputError "<path>: <reason>" (one line) for a file that cannot
// be read (input_file.h), is not a VDB file of format 222 … 224, is truncated or corrupt; a grid
// that is missing (the message lists the file's grids), not a FloatGrid or DoubleGrid, empty,
// whose tree holds more than kVdbTreeValuesMax values (vdb_layout.h), placed by a transform that
// is not an axis-aligned scale and translation (rotated, mirrored, a frustum), or holding a voxel
// that is negative or not finite (naming its index coordinate).
DensityGrid loadVdbDensity(const std::string& path, const std::string& gridName, std::uint32_t maxResolution);

// The same from the file's bytes (read by the caller: a scene's FileReader), `path` naming it.
DensityGrid decodeVdbDensity(const std::string& bytes, const std::string& path, const std::string& gridName,
                             std::uint32_t maxResolution);

}  // namespace photon
