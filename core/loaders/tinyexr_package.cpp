// tinyexr's implementation for the fuzz build (see loader_packages.cpp), in a file of its own: its
// PIZ Huffman decoder (getBits) shifts a signed 64-bit bit buffer left past its top, undefined in
// C++17 though every compiler wraps it, and the bits shifted out are never read (the result is
// masked to the low nBits). This file is compiled without UBSan's shift-base check
// (core/CMakeLists.txt) so that the fuzzer keeps looking at everything else; the input that found
// it is tests/fuzz/corpus/environment_loader_fuzz/piz-huffman-signed-shift.exr.
#define TINYEXR_IMPLEMENTATION
#include <tinyexr.h>
