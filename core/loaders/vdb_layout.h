// The layout of an OpenVDB file, walked byte by byte before OpenVDB reads any of it.
//
// OpenVDB 10's reader believes every length and count a file states. It reads an "uncompressed"
// chunk of n bytes into a buffer sized for the m values a node holds and checks n = m only
// afterwards (io::bloscFromStream, io::unzipFromStream: a heap overflow); it hands Blosc a chunk
// whose compressed size only Blosc's own header states; it allocates what a string's length or a
// chunk's size says (up to 4 GiB, or 2^63 bytes); it reads on past the end of a stream (a read that
// fails leaves the value it read into as it was); it leaks the nodes of a root table that names a
// child twice; and its trees expand ~30 times over in memory (a 2 KB leaf from ~60 bytes of Blosc).
//
// So the loader first walks the file here: its header, its grids' descriptors (skipping from one
// grid to the next by the grid offsets io::File writes, or through each grid's body in a stream
// without them) and, of the one grid it reads, every map, node, mask and chunk, each checked
// against the bytes that are there and against a cap on the tree's size, each compressed chunk
// decompressed once (OpenVDB throws when one does not decompress to its node's values, and leaks
// the node it was reading). Then OpenVDB reads a
// stream of that grid alone, without the metadata it does not need (the file's, and the grid's:
// its name, class, statistics and OpenVDB's delayed-load tables).
//
// The format (OpenVDB's io/Archive.cc, io/GridDescriptor.cc, io/Compression.h, tree/*Node.h), all
// numbers little-endian:
//   header      magic (8 bytes: 20 42 44 56 00 00 00 00), file format version (u32), library
//               major and minor version (u32 each), has-grid-offsets (1 byte), UUID (36 chars)
//   metadata    count (u32); each: name, type name (strings: u32 length + bytes), size (u32), value
//   grids       count (i32); each: descriptor = unique name, type ("Tree_float_5_4_3", with
//               "_HalfFloat" for 16-bit values), instance parent, then the grid's start, its tree
//               buffers' start and its end in the file (i64 each; 0 without grid offsets); then
//               the grid = compression flags (u32), metadata, transform (map type, map), tree
// A tree is its topology (root table, internal nodes of 32³ and 16³ children, leaf masks) and then
// its leaves' values, each node's values written by io::writeCompressedValues.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace photon {

// A VDB file begins with OpenVDB's magic number 0x56444220 ("VDB " as a big-endian word) stored as
// a little-endian 64-bit integer: the bytes 20 42 44 56 00 00 00 00.
inline constexpr char kVdbMagic[8] = {0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0};

// The most a tree handed to OpenVDB may hold: its leaf voxels plus the slots of its internal nodes
// (32768 and 4096 each) and root table. 2^30 values is 4 GiB of floats in OpenVDB's tree (8 of
// doubles) before Photon averages it down.
inline constexpr std::uint64_t kVdbTreeValuesMax = std::uint64_t(1) << 30;

// The file format versions Photon reads: 222 (OpenVDB 3.0, 2014: per-grid compression and node
// masks) to 224 (OpenVDB 4 and every later release).
inline constexpr std::uint32_t kVdbVersionFirst = 222;
inline constexpr std::uint32_t kVdbVersionLast = 224;

struct VdbGridEntry {
    std::string name;        // as written (OpenVDB's "\x1e<n>" suffix of repeated names cut off)
    std::string uniqueName;  // as in the file, the name instances refer to
    std::string type;        // "Tree_float_5_4_3", "Tree_vec3s_5_4_3", ... (no "_HalfFloat")
    bool halfFloat = false;  // values stored as 16-bit floats
    std::string instanceOf;  // the unique name of the grid whose tree it shares ("" for its own)
    std::size_t bodyStart = 0;  // the grid: compression flags, metadata, transform, tree
    std::size_t bodyEnd = 0;    // where it ends (its end offset, or found by walking it)
};

struct VdbLayout {
    std::uint32_t version = 0;       // the file format's
    std::uint32_t libraryMajor = 0;  // the version of the OpenVDB that wrote it
    std::uint32_t libraryMinor = 0;
    std::vector<VdbGridEntry> grids;  // in the file's order: all of them, or those before `unwalked`
    bool complete = true;             // false: a file without grid offsets (written as a stream)
    VdbGridEntry unwalked;            // whose walk stopped at this grid, a type it cannot step over
};

// The value type a grid's type names: "float" for "Tree_float_5_4_3".
std::string vdbValueType(const std::string& type);

// The header and grid descriptors of a VDB file. Throws InputError "<path>: <reason>" if it is not
// one, is of a format version outside 222 … 224, or is truncated or corrupt there.
VdbLayout readVdbLayout(const std::string& bytes, const std::string& path);

// Grid `index` of the file (a FloatGrid or DoubleGrid, or an instance of one), walked whole and
// rewritten as a VDB stream that holds it alone, for openvdb::io::Stream. Throws InputError if
// any length, count, node or chunk of it is not what OpenVDB can read safely, its transform is a
// frustum, or its tree holds more than `valuesMax` values (see kVdbTreeValuesMax).
std::string vdbGridStream(const std::string& bytes, const VdbLayout& layout, std::size_t index, const std::string& path,
                          std::uint64_t valuesMax = kVdbTreeValuesMax);

}  // namespace photon
