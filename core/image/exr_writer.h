// OpenEXR files: linear radiance as 32-bit float R, G, B scan lines, written by the OpenEXR library
// with its thread pool on every core. RLE is the default: lossless and, on rendered images, within
// 6% of ZIP's size at a third of its time (docs/performance.md, "Image files"); the others are
// there to be measured (photon-bench --image-writers).
#pragma once

#include <string>

#include "core/image/image.h"

namespace photon {

enum class ExrCompression { None, Rle, Zips, Zip, Piz };

const char* toString(ExrCompression compression);

// The whole EXR file. Throws RuntimeError if OpenEXR fails.
std::string encodeExr(const Image& image, ExrCompression compression = ExrCompression::Rle);

}  // namespace photon
