// PNG files (8-bit RGB, sRGB), encoded in bands of rows on every core. Each band is filtered (Sub)
// and deflated on its own by ISA-L's igzip (level 1) and ends with a sync flush, so that the bands'
// deflate streams, one after the other, make one valid zlib stream; each band becomes one IDAT
// chunk. Measured against stb_image_write, libpng, libspng, libdeflate and zlib in bands in
// docs/performance.md ("Image files (issue 19)"): at 1080p on 2 cores 9 ms of deflate instead of
// stb_image_write's 230 ms or libpng's 37 ms at its fastest, for files 7% larger than zlib's
// run-length matching and 12% larger than libpng at level 6.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace photon {

// Fills row y (0 at the top) with width × 3 bytes: R, G, B display values. Called from several
// threads at once, for different rows.
using PngRowSource = std::function<void(std::uint32_t y, unsigned char* rgb)>;

// The whole PNG file. Throws RuntimeError if the deflate encoder fails.
std::string encodePng(std::uint32_t width, std::uint32_t height, const PngRowSource& rows);

}  // namespace photon
