#include "core/loaders/vdb_layout.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>

#include <blosc.h>
#include <zlib.h>

#include "core/system/error.h"

namespace photon {
namespace {

using u64 = std::uint64_t;

// OpenVDB's compression flags (io/Compression.h) and the per-node flag of which values follow.
constexpr std::uint32_t kZip = 0x1;
constexpr std::uint32_t kActiveMask = 0x2;
constexpr std::uint32_t kBlosc = 0x4;
enum NodeValues : std::int8_t {
    kNoMaskOrInactive = 0,     // every inactive value is the background
    kNoMaskMinusBackground,    // ... or its negative
    kNoMaskOneInactive,        // one inactive value, stored
    kMaskNoInactive,           // a selection mask between ±background
    kMaskOneInactive,          // a selection mask between the background and one stored value
    kMaskTwoInactive,          // a selection mask between two stored values
    kAllValues,                // every value stored, active or not
};

// The grid types whose trees this walk knows (the standard 5-4-3 trees of plain values): the bytes
// a value takes in a node (tiles, backgrounds, inactive values) and in a chunk of half floats.
struct ValueLayout {
    const char* type;
    std::uint32_t bytes;
    std::uint32_t halfBytes;
};
constexpr ValueLayout kTrees[] = {
    {"Tree_float_5_4_3", 4, 2}, {"Tree_double_5_4_3", 8, 2}, {"Tree_int32_5_4_3", 4, 4}, {"Tree_int64_5_4_3", 8, 8},
    {"Tree_vec3s_5_4_3", 12, 6}, {"Tree_vec3d_5_4_3", 24, 6}, {"Tree_vec3i_5_4_3", 12, 12},
};

const ValueLayout* treeLayout(const std::string& type) {
    for (const ValueLayout& t : kTrees) {
        if (type == t.type) {
            return &t;
        }
    }
    return nullptr;
}

// What a map of each type takes after its type name (math/Maps.h, each map's read()): Vec3d
// members (24 bytes) or a Mat4d (128).
constexpr std::pair<const char*, std::uint32_t> kLinearMaps[] = {
    {"TranslationMap", 24},           // translation
    {"ScaleMap", 5 * 24},             // scale, voxel size, inverse scale, its square, inverse twice
    {"UniformScaleMap", 5 * 24},      // the same
    {"ScaleTranslateMap", 6 * 24},    // translation, then ScaleMap's five
    {"UniformScaleTranslateMap", 6 * 24},
    {"AffineMap", 128},               // the matrix
    {"UnitaryMap", 128},              // an AffineMap
};
constexpr const char* kFrustumMap = "NonlinearFrustumMap";

std::string gridLabel(const std::string& name) { return "grid " + printable(quote(name)); }

// A cursor over the file's bytes that refuses to step past their end. `where` names what is being
// read, for the messages.
struct Walk {
    const std::string& b;
    std::size_t at;
    const std::string& path;
    std::string where;

    u64 left() const { return b.size() - at; }
    [[noreturn]] void corrupt(const std::string& reason) const {
        throw InputError(path + ": corrupt VDB file: " + where + ": " + reason);
    }
    void need(u64 n) const {
        if (n > left()) {
            throw InputError(path + ": truncated VDB file: it ends in " + where);
        }
    }
    const char* take(u64 n) {
        need(n);
        const char* p = b.data() + at;
        at += std::size_t(n);
        return p;
    }
    void skip(u64 n) { take(n); }
    template <typename T>
    T number() {
        T x;
        std::memcpy(&x, take(sizeof(T)), sizeof(T));  // OpenVDB writes the machine's order: little-endian
        return x;
    }
    std::uint8_t u8() { return number<std::uint8_t>(); }
    std::uint32_t u32() { return number<std::uint32_t>(); }
    std::int32_t i32() { return number<std::int32_t>(); }
    std::int64_t i64() { return number<std::int64_t>(); }
    // A string: its length (u32), then its bytes.
    std::string text() {
        std::uint32_t n = u32();
        return std::string(take(n), n);
    }
};

u64 bitsOn(const char* mask, std::size_t bytes) {
    u64 n = 0;
    for (std::size_t i = 0; i < bytes; i += 8) {
        std::uint64_t word;
        std::memcpy(&word, mask + i, 8);
        n += u64(__builtin_popcountll(word));
    }
    return n;
}

bool bitsOverlap(const char* a, const char* b, std::size_t bytes) {
    for (std::size_t i = 0; i < bytes; ++i) {
        if ((a[i] & b[i]) != 0) {
            return true;
        }
    }
    return false;
}

// A metadata table (MetaMap::readMeta), stepped over by each entry's stated size: OpenVDB reads a
// typed value by its type's size and a string or an unknown type by the stated one, which agree
// in every file it writes (and none of it reaches OpenVDB here).
void skipMetadata(Walk& w) {
    std::uint32_t count = w.u32();
    for (std::uint32_t i = 0; i < count; ++i) {
        w.text();  // name
        w.text();  // type name
        w.skip(w.u32());
    }
}

// A transform (math::Transform::read): a map's type name and its members. A frustum holds a
// bounding box, its taper and depth, then a linear map of its own.
bool skipTransform(Walk& w, bool frustumAllowed) {
    std::string type = w.text();
    if (type == kFrustumMap && frustumAllowed) {
        w.skip(48 + 8 + 8);  // BBoxd, taper, depth
        type = w.text();
        frustumAllowed = false;  // OpenVDB would nest them without end (and overflow its stack)
    }
    for (const auto& [name, bytes] : kLinearMaps) {
        if (type == name) {
            w.skip(bytes);
            return true;
        }
    }
    if (type == kFrustumMap) {
        return false;
    }
    w.corrupt("a transform of the unknown type " + printable(quote(type)));
}

// A tree (Tree::readTopology, Tree::readBuffers) walked as OpenVDB reads it.
struct TreeWalk {
    Walk& w;
    ValueLayout value;
    bool half;                 // values in chunks are 16-bit floats
    std::uint32_t compression;
    u64 valuesMax;
    const std::string& grid;   // its label, for messages
    u64 values = 0;            // slots of the nodes met so far (see kVdbTreeValuesMax)
    u64 leaves = 0;
    std::vector<char> scratch; // a chunk's values, decompressed to see that they decompress

    void hold(u64 slots) {
        values += slots;
        if (values > valuesMax) {
            throw InputError(w.path + ": " + grid + " holds more than " + std::to_string(valuesMax) +
                             " voxels and tiles in its tree, more than Photon reads (average it down first)");
        }
    }

    // A node's n values as io::readCompressedValues reads them: a byte saying which inactive
    // values are stored, those values and a selection mask, then the values themselves (only
    // the active ones under mask compression) raw or as one Blosc or zlib chunk.
    void nodeValues(u64 n, u64 active) {
        auto flag = std::int8_t(w.u8());
        if (flag == kNoMaskOneInactive || flag == kMaskOneInactive || flag == kMaskTwoInactive) {
            w.skip(flag == kMaskTwoInactive ? 2 * value.bytes : value.bytes);
        }
        if (flag == kMaskNoInactive || flag == kMaskOneInactive || flag == kMaskTwoInactive) {
            w.skip(n / 8);
        }
        u64 count = (compression & kActiveMask) && flag != kAllValues ? active : n;
        if (half && count == 0) {
            return;  // io::HalfReader reads nothing at all for no values
        }
        u64 bytes = count * (half ? value.halfBytes : value.bytes);
        if (compression & kBlosc) {
            chunk(bytes, true);
        } else if (compression & kZip) {
            chunk(bytes, false);
        } else {
            w.skip(bytes);
        }
    }

    // A compressed chunk: its size (i64), negative for the bytes stored as they are, which
    // OpenVDB reads into the node's buffer before it compares the size with the buffer's. A
    // compressed one is decompressed here once: OpenVDB throws when a chunk does not decompress
    // to the node's values, and a node being read when it throws is leaked.
    void chunk(u64 expected, bool blosc) {
        std::int64_t size = w.i64();
        if (size <= 0) {
            u64 stored = u64(0) - u64(size);
            if (stored != expected) {
                w.corrupt("an uncompressed chunk of " + std::to_string(stored) + " bytes where " + std::to_string(expected) +
                          " are due");
            }
            w.skip(stored);
            return;
        }
        w.need(u64(size));
        if (blosc) {
            // Blosc's 16-byte header: versions, flags, type size, then the sizes uncompressed, of a
            // block and compressed (u32 each). blosc_decompress_ctx is not told the chunk's size
            // and reads as far as the compressed size the header states.
            const char* header = w.b.data() + w.at;
            std::uint32_t nbytes = 0;
            std::uint32_t cbytes = 0;
            if (size >= 16) {
                std::memcpy(&nbytes, header + 4, 4);
                std::memcpy(&cbytes, header + 12, 4);
            }
            if (size < 16 || cbytes < 16 || cbytes > u64(size) || nbytes != expected) {
                w.corrupt("a Blosc chunk of " + std::to_string(size) + " bytes whose header states " + std::to_string(cbytes) +
                          " bytes of " + std::to_string(nbytes) + " (" + std::to_string(expected) + " are due)");
            }
        }
        scratch.resize(std::max<std::size_t>(std::size_t(expected), 1));
        const char* data = w.take(u64(size));
        bool whole = false;
        if (blosc) {
            whole = blosc_decompress_ctx(data, scratch.data(), std::size_t(expected), 1) == std::int64_t(expected);
        } else {
            uLongf length = uLongf(expected);
            whole = uncompress(reinterpret_cast<Bytef*>(scratch.data()), &length, reinterpret_cast<const Bytef*>(data),
                               uLong(size)) == Z_OK &&
                    length == expected;
        }
        if (!whole) {
            w.corrupt(std::string("a ") + (blosc ? "Blosc" : "zlib") + " chunk that does not decompress to the " +
                      std::to_string(expected) + " bytes due");
        }
    }

    // An internal node's topology: child and value masks, its values, then its children.
    void internalNode(int log2Dim) {
        const u64 slots = u64(1) << (3 * log2Dim);
        hold(slots);
        const char* childMask = w.take(slots / 8);
        const char* valueMask = w.take(slots / 8);
        if (bitsOverlap(childMask, valueMask, slots / 8)) {
            w.corrupt("a node with a child and an active tile in one place");
        }
        nodeValues(slots, bitsOn(valueMask, slots / 8));
        u64 children = bitsOn(childMask, slots / 8);
        for (u64 i = 0; i < children; ++i) {
            if (log2Dim == 5) {
                internalNode(4);
            } else {
                hold(512);  // a leaf of 8³ voxels: its value mask
                w.skip(64);
                ++leaves;
            }
        }
    }

    void walk() {
        std::int32_t buffers = w.i32();
        if (buffers != 1) {
            w.corrupt("a tree of " + std::to_string(buffers) + " buffers (trees have one)");
        }
        w.skip(value.bytes);  // the background
        std::uint32_t tiles = w.u32();
        std::uint32_t children = w.u32();
        // The root table's keys: node origins, multiples of 4096, each at most once (OpenVDB
        // keeps the last node of a key and leaks the others).
        std::vector<std::array<std::int32_t, 3>> keys;
        auto key = [&] {
            std::array<std::int32_t, 3> k{w.i32(), w.i32(), w.i32()};
            for (std::int32_t c : k) {
                if ((c & 4095) != 0) {
                    w.corrupt("a root node at (" + std::to_string(k[0]) + ", " + std::to_string(k[1]) + ", " +
                              std::to_string(k[2]) + "), not a multiple of 4096");
                }
            }
            keys.push_back(k);
        };
        for (std::uint32_t i = 0; i < tiles; ++i) {
            hold(1);
            key();
            w.skip(value.bytes);
            if (w.u8() > 1) {
                w.corrupt("a tile whose active flag is neither 0 nor 1");
            }
        }
        for (std::uint32_t i = 0; i < children; ++i) {
            key();
            internalNode(5);
        }
        std::sort(keys.begin(), keys.end());
        if (std::adjacent_find(keys.begin(), keys.end()) != keys.end()) {
            w.corrupt("two root nodes at one place");
        }
        // The leaves' buffers: each its value mask again, then its values.
        for (u64 i = 0; i < leaves; ++i) {
            const char* mask = w.take(64);
            nodeValues(512, bitsOn(mask, 64));
        }
    }
};

// The parts of a grid's body: where its transform starts and its tree starts and ends.
struct GridBody {
    std::uint32_t compression = 0;
    std::size_t transform = 0;
    std::size_t tree = 0;
    std::size_t end = 0;
};

// Walks a grid's body from its start. Without a known tree layout (`value` null) only up to its
// tree; a frustum transform is refused unless `frustumAllowed`.
GridBody walkBody(const std::string& bytes, const VdbGridEntry& entry, const ValueLayout* value, bool frustumAllowed,
                  u64 valuesMax, const std::string& path) {
    const std::string label = gridLabel(entry.name);
    Walk w{bytes, entry.bodyStart, path, "the metadata of " + label};
    GridBody body;
    body.compression = w.u32();
    if ((body.compression & ~(kZip | kActiveMask | kBlosc)) != 0) {
        w.corrupt("compression flags " + std::to_string(body.compression));
    }
    skipMetadata(w);
    w.where = "the transform of " + label;
    body.transform = w.at;
    if (!skipTransform(w, frustumAllowed)) {
        throw InputError(path + ": " + label + " is placed by a NonlinearFrustumMap (a frustum); Photon reads grids whose "
                                               "transform is an axis-aligned scale and translation");
    }
    body.tree = w.at;
    if (entry.instanceOf.empty() && value) {
        w.where = "the tree of " + label;
        // Only real values are stored as half floats (io::RealToHalf); an integer grid so marked is not.
        bool half = entry.halfFloat && value->halfBytes != value->bytes;
        TreeWalk tree{w, *value, half, body.compression, valuesMax, label};
        tree.walk();
    }
    body.end = w.at;
    if (entry.bodyEnd != 0 && body.end > entry.bodyEnd) {
        w.corrupt("it runs " + std::to_string(body.end - entry.bodyEnd) + " bytes past the grid's end offset");
    }
    return body;
}

void putU32(std::string& s, std::uint32_t x) { s.append(reinterpret_cast<const char*>(&x), 4); }
void putI64(std::string& s, std::int64_t x) { s.append(reinterpret_cast<const char*>(&x), 8); }
void putText(std::string& s, const std::string& text) {
    putU32(s, std::uint32_t(text.size()));
    s += text;
}

}  // namespace

std::string vdbValueType(const std::string& type) {
    const std::string prefix = "Tree_";
    std::size_t end = type.find('_', prefix.size());
    return type.rfind(prefix, 0) == 0 && end != std::string::npos ? type.substr(prefix.size(), end - prefix.size()) : type;
}

VdbLayout readVdbLayout(const std::string& bytes, const std::string& path) {
    Walk w{bytes, 0, path, "its header"};
    if (std::memcmp(w.take(sizeof(kVdbMagic)), kVdbMagic, sizeof(kVdbMagic)) != 0) {
        w.corrupt("not an OpenVDB file (by its first 8 bytes)");
    }
    VdbLayout layout;
    layout.version = w.u32();
    if (layout.version < kVdbVersionFirst || layout.version > kVdbVersionLast) {
        throw InputError(path + ": a VDB file of format version " + std::to_string(layout.version) + "; Photon reads versions " +
                         std::to_string(kVdbVersionFirst) + " to " + std::to_string(kVdbVersionLast) +
                         " (OpenVDB 3.0 and every later release)");
    }
    layout.libraryMajor = w.u32();
    layout.libraryMinor = w.u32();
    bool offsets = w.u8() != 0;
    w.skip(36);  // the UUID, as text
    w.where = "the file's metadata";
    skipMetadata(w);
    w.where = "its grid count";
    std::int32_t count = w.i32();
    if (count < 0) {
        w.corrupt(std::to_string(count) + " grids");
    }
    for (std::int32_t i = 0; i < count; ++i) {
        w.where = "the descriptor of grid " + std::to_string(i);
        VdbGridEntry g;
        g.uniqueName = w.text();
        g.name = g.uniqueName.substr(0, g.uniqueName.find('\x1e'));  // GridDescriptor's separator
        g.type = w.text();
        const std::string half = "_HalfFloat";
        if (g.type.size() > half.size() && g.type.compare(g.type.size() - half.size(), half.size(), half) == 0) {
            g.type.resize(g.type.size() - half.size());
            g.halfFloat = true;
        }
        g.instanceOf = w.text();
        w.i64();  // the grid's start,
        w.i64();  // its buffers' start,
        std::int64_t end = w.i64();  // and its end (all 0 without offsets)
        g.bodyStart = w.at;
        if (offsets) {
            if (end > 0 && u64(end) > bytes.size()) {
                throw InputError(path + ": truncated VDB file: " + gridLabel(g.name) + " ends at byte " + std::to_string(end) +
                                 ", past the file's " + std::to_string(bytes.size()));
            }
            if (end < std::int64_t(w.at)) {
                w.corrupt(gridLabel(g.name) + " ends at byte " + std::to_string(end) + ", before it begins");
            }
            g.bodyEnd = std::size_t(end);
        } else {
            // A stream: the next descriptor follows the grid's body, found by walking it.
            const ValueLayout* value = treeLayout(g.type);
            if (!value) {
                layout.complete = false;
                layout.unwalked = g;
                return layout;
            }
            g.bodyEnd = walkBody(bytes, g, value, true, std::numeric_limits<u64>::max(), path).end;
        }
        w.at = g.bodyEnd;
        layout.grids.push_back(g);
    }
    return layout;
}

std::string vdbGridStream(const std::string& bytes, const VdbLayout& layout, std::size_t index, const std::string& path,
                          std::uint64_t valuesMax) {
    const VdbGridEntry& grid = layout.grids.at(index);
    // An instance shares another grid's tree: its own transform, the other's tree (and that
    // tree's compression and half floats).
    const VdbGridEntry* owner = &grid;
    if (!grid.instanceOf.empty()) {
        auto parent = std::find_if(layout.grids.begin(), layout.grids.end(), [&](const VdbGridEntry& g) {
            return g.uniqueName == grid.instanceOf && g.instanceOf.empty();
        });
        if (parent == layout.grids.end()) {
            throw InputError(path + ": corrupt VDB file: " + gridLabel(grid.name) +
                             " is an instance of a grid the file does not hold");
        }
        owner = &*parent;
    }
    const ValueLayout* value = treeLayout(owner->type);
    if (!value || owner->type != grid.type || (owner->type != kTrees[0].type && owner->type != kTrees[1].type)) {
        throw InputError(path + ": " + gridLabel(grid.name) + " is a " + printable(quote(owner->type)) +
                         ", not OpenVDB's standard Tree_float_5_4_3 or Tree_double_5_4_3 (densities are grids of floats; "
                         "another tree configuration, or a damaged type name)");
    }
    GridBody own = walkBody(bytes, grid, value, false, valuesMax, path);
    GridBody tree = owner == &grid ? own : walkBody(bytes, *owner, value, true, valuesMax, path);

    // The stream: a header without grid offsets, no file metadata, one grid.
    std::string s(kVdbMagic, sizeof(kVdbMagic));
    putU32(s, layout.version);
    putU32(s, layout.libraryMajor);
    putU32(s, layout.libraryMinor);
    s += '\0';
    s += "00000000-0000-0000-0000-000000000000";
    putU32(s, 0);
    putU32(s, 1);
    putText(s, grid.uniqueName);
    putText(s, grid.type + (owner->halfFloat ? "_HalfFloat" : ""));
    putText(s, "");
    putI64(s, 0);
    putI64(s, 0);
    putI64(s, 0);
    putU32(s, tree.compression);
    // Its metadata: only the flag of half floats, which OpenVDB keeps as metadata (it replaces
    // what the descriptor's "_HalfFloat" set when it reads the grid's metadata).
    if (owner->halfFloat) {
        putU32(s, 1);
        putText(s, "is_saved_as_half_float");
        putText(s, "bool");
        putU32(s, 1);
        s += '\1';
    } else {
        putU32(s, 0);
    }
    s.append(bytes, own.transform, own.tree - own.transform);
    s.append(bytes, tree.tree, tree.end - tree.tree);
    return s;
}

}  // namespace photon
