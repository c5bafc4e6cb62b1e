#include "core/loaders/vdb_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <istream>
#include <streambuf>
#include <vector>

#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>

#include "core/loaders/vdb_layout.h"
#include "core/system/error.h"
#include "core/system/input_file.h"
#include "core/system/numbers.h"

namespace photon {
namespace {

using u64 = std::uint64_t;
using openvdb::Coord;
using openvdb::CoordBBox;

// A grid averaged down to at most kDensityResolutionMax voxels an axis holds at most 2^27 of them,
// within kDensityVoxelsMax (2^28): the check in resample() never fires for one grid, and the total
// of a scene's grids is the scene's to check.
static_assert(u64(kDensityResolutionMax) * kDensityResolutionMax * kDensityResolutionMax <= kDensityVoxelsMax);

// The bytes as a read-only stream that OpenVDB reads, without the copy an istringstream makes.
class MemoryBuffer : public std::streambuf {
public:
    explicit MemoryBuffer(const std::string& bytes) {
        char* begin = const_cast<char*>(bytes.data());  // never written: only the get area is set
        setg(begin, begin, begin + bytes.size());
    }

protected:
    pos_type seekoff(off_type offset, std::ios_base::seekdir from, std::ios_base::openmode which) override {
        off_type size = egptr() - eback();
        off_type base = from == std::ios_base::beg ? 0 : from == std::ios_base::cur ? gptr() - eback() : size;
        if (!(which & std::ios_base::in) || offset < -base || offset > size - base) {
            return pos_type(off_type(-1));
        }
        setg(eback(), eback() + base + offset, egptr());
        return pos_type(base + offset);
    }
    pos_type seekpos(pos_type at, std::ios_base::openmode which) override {
        return seekoff(off_type(at), std::ios_base::beg, which);
    }
};

// openvdb::initialize() registers the grid, map and metadata types the reader creates by name.
void initializeOpenVdb() {
    static const bool initialized = (openvdb::initialize(), true);  // once, thread-safe (a static's initialiser)
    (void)initialized;
}

// A grid's name as messages quote it.
std::string label(const std::string& name) { return printable(quote(name)); }

// A grid's value type as messages show it: "float", "vec3s"; quoted and cut if it is not a word.
std::string typeLabel(const std::string& type) {
    std::string value = vdbValueType(type);
    auto wordChar = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    bool word = !value.empty() && value.size() <= 24 && std::all_of(value.begin(), value.end(), wordChar);
    // OpenVDB's standard configuration by its value type alone; any other tree by its whole type.
    bool standard = type == "Tree_" + value + "_5_4_3";
    return word && standard ? value : label(standard ? value : type);
}

// The grids of a file, for the messages that ask for one of them: 'density' (float), 'v' (vec3s).
std::string gridList(const VdbLayout& layout) {
    auto entry = [](const VdbGridEntry& g) { return label(g.name) + " (" + typeLabel(g.type) + ")"; };
    std::string list;
    for (std::size_t i = 0; i < layout.grids.size() && i < 12; ++i) {
        list += (i ? ", " : "") + entry(layout.grids[i]);
    }
    if (layout.grids.size() > 12) {
        list += " and " + std::to_string(layout.grids.size() - 12) + " more";
    }
    if (!layout.complete) {
        list += (list.empty() ? "" : ", ") + entry(layout.unwalked) +
                " and whatever follows it in this file without grid offsets (written as a stream), which Photon "
                "cannot step over";
    }
    return list.empty() ? "none" : list;
}

// The grid asked for: by name, or the first grid of floats (FloatGrid, then DoubleGrid).
std::size_t pickGrid(const VdbLayout& layout, const std::string& name, const std::string& path) {
    const std::vector<VdbGridEntry>& grids = layout.grids;
    auto isType = [&](std::size_t i, const char* type) { return grids[i].type == type; };
    auto scalar = [&](std::size_t i) { return isType(i, "Tree_float_5_4_3") || isType(i, "Tree_double_5_4_3"); };
    auto first = [&](auto match) {
        std::size_t i = 0;
        while (i < grids.size() && !match(i)) {
            ++i;
        }
        return i;
    };
    std::size_t found = name.empty() ? first([&](std::size_t i) { return isType(i, "Tree_float_5_4_3"); })
                                     : first([&](std::size_t i) { return grids[i].name == name; });
    if (name.empty() && found == grids.size()) {
        found = first([&](std::size_t i) { return isType(i, "Tree_double_5_4_3"); });
    }
    if (grids.empty() && layout.complete) {
        throw InputError(path + ": a VDB file without grids");
    }
    if (found == grids.size()) {
        std::string missing = name.empty() ? "no grid of floats (FloatGrid or DoubleGrid: OpenVDB's Tree_float_5_4_3 or Tree_double_5_4_3)"
                                           : "no grid named " + label(name);
        throw InputError(path + ": " + missing + " in the file; its grids: " + gridList(layout));
    }
    if (!scalar(found)) {
        std::string value = vdbValueType(grids[found].type);
        // A float or double tree of another configuration (or a damaged type name) is no grid of
        // "float values" to refuse as one.
        std::string what = value == "float" || value == "double"
                               ? "a tree of type " + label(grids[found].type) +
                                     ", not OpenVDB's standard Tree_float_5_4_3 or Tree_double_5_4_3 (another tree "
                                     "configuration, or a damaged type name)"
                               : typeLabel(grids[found].type) + " values; densities are grids of floats (FloatGrid or DoubleGrid)";
        throw InputError(path + ": grid " + label(name) + " holds " + what + "; the file's grids: " + gridList(layout));
    }
    return found;
}

// The index-to-world map as a scale and a translation per axis: OpenVDB's maps are affine,
// world = index · M with row vectors, so the scale is M's diagonal and the translation its last
// row. A rotation, shear or mirror (a voxel grid that does not tile an axis-aligned box with
// its own axes) or a frustum is refused.
struct AxisMap {
    glm::dvec3 scale;
    glm::dvec3 translation;
};

AxisMap axisMap(const openvdb::GridBase& grid, const std::string& name, const std::string& path) {
    const openvdb::math::MapBase& map = *grid.transform().baseMap();
    std::string where = path + ": grid " + label(name) + " is placed by ";
    if (!map.isLinear()) {
        throw InputError(where + "a " + map.type() +
                         " (a frustum); Photon reads grids whose transform is an axis-aligned scale and translation");
    }
    openvdb::Mat4d m = map.getAffineMap()->getMat4();
    AxisMap axes;
    for (int i = 0; i < 3; ++i) {
        axes.scale[i] = m(i, i);
        axes.translation[i] = m(3, i);
        for (int j = 0; j < 3; ++j) {
            if (i != j && !(std::abs(m(i, j)) <= 1e-9 * std::max(std::abs(m(i, i)), std::abs(m(j, j))))) {
                throw InputError(where + "a rotated or sheared " + map.type() +
                                 "; Photon reads grids whose transform is an axis-aligned scale and translation");
            }
        }
        if (!(axes.scale[i] > 0.0) || !std::isfinite(axes.scale[i]) || !std::isfinite(axes.translation[i])) {
            throw InputError(where + "a " + map.type() + " whose scale along " + "xyz"[i] + " is " + formatNumber(axes.scale[i]) +
                             (axes.scale[i] < 0.0 ? " (a mirror)" : "") + "; voxels are placed by positive, finite scales");
        }
    }
    return axes;
}

// Values must be densities: finite and ≥ 0. `where` names the voxel or tile.
void checkValue(double value, const std::string& name, const std::string& path, const std::function<std::string()>& where) {
    if (!std::isfinite(float(value)) || value < 0.0) {
        throw InputError(path + ": grid " + label(name) + ": " + where() + " is " +
                         (std::isfinite(float(value)) ? "negative (" + formatNumber(value) + "); densities cannot be negative"
                                                      : "not finite as a 32-bit float (" + formatNumber(value) + ")"));
    }
}

// Every output voxel a density (the background shows where no active voxel or tile covers one,
// which the active voxel count alone does not tell; a block's mean can round below 0).
void checkDensities(const DensityGrid& out, const std::string& name, const std::string& path) {
    for (std::size_t i = 0; i < out.density.size(); ++i) {
        checkValue(double(out.density[i]), name, path, [&] { return "output voxel " + std::to_string(i); });
    }
}

std::string coordText(const Coord& c) {
    return "(" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) + ")";
}

// The grid's active voxels resampled into a DensityGrid. The box is the bounding box of the active
// voxels; a voxel centre takes the value of the voxel it lies in (the background where that is
// inactive). Wider than maxResolution, the box is cut into blocks of f×f×f voxels (f the least
// that fits), each block one voxel of their mean, where a block reaching past the box counts the
// background beyond it: the sum of densities times the voxel volume, the integral, is kept.
template <typename GridT>
DensityGrid resample(const GridT& grid, const std::string& name, std::uint32_t maxResolution, const AxisMap& axes,
                     const std::string& path) {
    using ValueT = typename GridT::ValueType;
    CoordBBox box = grid.evalActiveVoxelBoundingBox();
    if (grid.activeVoxelCount() == 0 || box.empty()) {
        throw InputError(path + ": grid " + label(name) + " has no active voxels (an empty grid)");
    }
    // Extents in 64 bits: a box may span the whole 32-bit index space.
    std::int64_t extent[3];
    std::int64_t largest = 0;
    for (int a = 0; a < 3; ++a) {
        extent[a] = std::int64_t(box.max()[a]) - box.min()[a] + 1;
        largest = std::max(largest, extent[a]);
    }
    std::int64_t f = (largest + maxResolution - 1) / maxResolution;
    DensityGrid out;
    for (int a = 0; a < 3; ++a) {
        out.resolution[a] = std::uint32_t((extent[a] + f - 1) / f);
    }
    u64 count = u64(out.resolution.x) * out.resolution.y * out.resolution.z;
    if (count > kDensityVoxelsMax) {  // never, by the static_assert above; checked before allocating
        throw InputError(path + ": grid " + label(name) + " would be " + std::to_string(count) + " voxels, more than the " +
                         std::to_string(kDensityVoxelsMax) + " a scene holds");
    }
    for (int a = 0; a < 3; ++a) {
        double first = double(box.min()[a]) - 0.5;
        out.lower[a] = float(axes.translation[a] + axes.scale[a] * first);
        out.upper[a] = float(axes.translation[a] + axes.scale[a] * (first + double(out.resolution[a]) * double(f)));
        if (!std::isfinite(out.lower[a]) || !std::isfinite(out.upper[a]) || !(out.lower[a] < out.upper[a])) {
            throw InputError(path + ": grid " + label(name) + " spans " + formatNumber(out.lower[a]) + " to " +
                             formatNumber(out.upper[a]) + " along " + "xyz"[a] + ", not a box of 32-bit floats");
        }
    }

    // The background counts where a voxel of the (padded) box is inactive.
    const double background = double(grid.background());
    double padded = double(out.resolution.x) * double(out.resolution.y) * double(out.resolution.z) * double(f) * double(f) * double(f);
    if (double(grid.activeVoxelCount()) < padded) {
        checkValue(background, name, path, [] { return std::string("its background (the value of inactive voxels)"); });
    }
    // The output voxel of an index coordinate inside the box.
    auto cell = [&](const Coord& c) {
        std::size_t i[3];
        for (int a = 0; a < 3; ++a) {
            i[a] = std::size_t((std::int64_t(c[a]) - box.min()[a]) / f);
        }
        return i[0] + out.resolution.x * (i[1] + std::size_t(out.resolution.y) * i[2]);
    };
    // Active tiles (above the leaves) are boxes of one value, inside the active box: each is
    // visited output voxel by output voxel with the number of its voxels there, so a tile of
    // 4096³ voxels costs no more than the output voxels it covers.
    auto forEachTileCell = [&](auto visit) {
        typename GridT::ValueOnCIter tile = grid.cbeginValueOn();
        tile.setMaxDepth(GridT::ValueOnCIter::LEAF_DEPTH - 1);
        for (; tile; ++tile) {
            CoordBBox b = tile.getBoundingBox();
            checkValue(double(*tile), name, path, [&] { return "the tile at " + coordText(b.min()); });
            std::int64_t first[3], last[3];
            for (int a = 0; a < 3; ++a) {
                first[a] = (std::int64_t(b.min()[a]) - box.min()[a]) / f;
                last[a] = (std::int64_t(b.max()[a]) - box.min()[a]) / f;
            }
            // Voxels of the tile along axis a inside output voxel i.
            auto overlap = [&](int a, std::int64_t i) {
                std::int64_t start = box.min()[a] + i * f;
                return double(std::min<std::int64_t>(b.max()[a], start + f - 1) - std::max<std::int64_t>(b.min()[a], start) + 1);
            };
            for (std::int64_t z = first[2]; z <= last[2]; ++z) {
                for (std::int64_t y = first[1]; y <= last[1]; ++y) {
                    for (std::int64_t x = first[0]; x <= last[0]; ++x) {
                        std::size_t i = std::size_t(x) + out.resolution.x * (std::size_t(y) + std::size_t(out.resolution.y) *
                                                                                                   std::size_t(z));
                        visit(i, overlap(0, x) * overlap(1, y) * overlap(2, z), *tile);
                    }
                }
            }
        }
    };

    out.density.assign(std::size_t(count), float(background));
    if (f == 1) {
        for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
            for (auto v = leaf->cbeginValueOn(); v; ++v) {
                checkValue(double(*v), name, path, [&] { return "voxel " + coordText(v.getCoord()); });
                out.density[cell(v.getCoord())] = float(*v);
            }
        }
        forEachTileCell([&](std::size_t i, double, ValueT value) { out.density[i] = float(value); });
        checkDensities(out, name, path);
        return out;
    }
    // Sums of each block's differences from the background, in double (a block adds up f³ voxels;
    // at most 1 GiB for 512³ blocks, for the time of the loop).
    std::vector<double> sum(std::size_t(count), 0.0);
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
        for (auto v = leaf->cbeginValueOn(); v; ++v) {
            checkValue(double(*v), name, path, [&] { return "voxel " + coordText(v.getCoord()); });
            sum[cell(v.getCoord())] += double(*v) - background;
        }
    }
    forEachTileCell([&](std::size_t i, double voxels, ValueT value) { sum[i] += voxels * (double(value) - background); });
    const double volume = double(f) * double(f) * double(f);
    for (std::size_t i = 0; i < sum.size(); ++i) {
        out.density[i] = float(background + sum[i] / volume);
    }
    checkDensities(out, name, path);
    return out;
}

}  // namespace

DensityGrid loadVdbDensity(const std::string& path, const std::string& gridName, std::uint32_t maxResolution) {
    return decodeVdbDensity(readInputFile(path, kVdbFileLimit, "OpenVDB file"), path, gridName, maxResolution);
}

DensityGrid decodeVdbDensity(const std::string& bytes, const std::string& path, const std::string& gridName,
                             std::uint32_t maxResolution) {
    if (maxResolution < 1 || maxResolution > kDensityResolutionMax) {
        throw InputError(path + ": a density grid of at most " + std::to_string(maxResolution) +
                         " voxels along an axis asked for; 1 to " + std::to_string(kDensityResolutionMax) + " are possible");
    }
    if (bytes.size() > kVdbFileLimit) {
        throw InputError(path + ": an OpenVDB file of " + std::to_string(bytes.size()) + " bytes, more than the " +
                         std::to_string(kVdbFileLimit) + " Photon reads");
    }
    if (bytes.size() < sizeof(kVdbMagic) || std::memcmp(bytes.data(), kVdbMagic, sizeof(kVdbMagic)) != 0) {
        throw InputError(path + ": " + (bytes.empty() ? "an empty file" : "not an OpenVDB file (by its first 8 bytes)") +
                         "; media's density grids are .vdb files");
    }
    // Every length, count and chunk of the file's grid checked before OpenVDB reads it: see
    // vdb_layout.h for what OpenVDB's reader would do with them.
    VdbLayout layout = readVdbLayout(bytes, path);
    std::size_t index = pickGrid(layout, gridName, path);
    const std::string name = layout.grids[index].name;
    const std::string stream = vdbGridStream(bytes, layout, index, path);

    initializeOpenVdb();
    try {
        MemoryBuffer buffer(stream);
        std::istream in(&buffer);
        in.exceptions(std::ios::failbit | std::ios::badbit);  // a read past the end throws, never goes on
        // OpenVDB 10 copies the whole stream into a temporary file to memory-map it, unless
        // delayLoad is false.
        openvdb::io::Stream reader(in, /*delayLoad=*/false);
        openvdb::GridPtrVecPtr grids = reader.getGrids();
        if (!grids || grids->size() != 1 || !grids->front()) {
            throw InputError(path + ": OpenVDB did not read grid " + label(name));
        }
        const openvdb::GridBase::Ptr& grid = grids->front();
        AxisMap axes = axisMap(*grid, name, path);
        if (auto floats = openvdb::gridPtrCast<openvdb::FloatGrid>(grid)) {
            return resample(*floats, name, maxResolution, axes, path);
        }
        if (auto doubles = openvdb::gridPtrCast<openvdb::DoubleGrid>(grid)) {
            return resample(*doubles, name, maxResolution, axes, path);
        }
        throw InputError(path + ": OpenVDB read grid " + label(name) + " as " + grid->type() + ", not a grid of floats");
    } catch (const InputError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw;  // out of memory is the machine's failure, not the file's
    } catch (const std::exception& e) {
        // What the walk above does not foresee: openvdb::Exception ("ArithmeticError: Inversion
        // of singular 4x4 matrix" for a map that cannot be inverted), std::ios_base::failure.
        throw InputError(path + ": corrupt or unreadable OpenVDB file: " + printable(e.what()));
    }
}

}  // namespace photon
