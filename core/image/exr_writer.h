// OpenEXR files: linear radiance as 32-bit float R, G, B, written by the OpenEXR library with its
// thread pool on every core. The default, RLE in scan lines, is lossless and the fastest of the
// compressions on rendered images: within 6% of ZIP's size (the low mantissa bits of a render are
// noise to every lossless coder) at a fifth of its time. OpenEXR 3.1 compresses RLE's one-line
// chunks on one thread only; 128×128 tiles are compressed in parallel (1080p on 2 cores: 24 ms
// instead of 38), but Photon's environment loader reads scan-line files only, so tiles are an
// option, not the default. Every choice is there to be measured (photon-bench --image-writers;
// docs/performance.md, "Image files (issue 19)").
#pragma once

#include <string>
#include <vector>

#include "core/image/image.h"

namespace photon {

enum class ExrCompression { None, Rle, Zips, Zip, Piz };
// Scan lines, or tiles of 128×128 pixels.
enum class ExrLayout { Scanlines, Tiles };

const char* toString(ExrCompression compression);
const char* toString(ExrLayout layout);

// The whole EXR file: the image as R, G, B and each layer's channels. Throws RuntimeError if
// OpenEXR fails.
std::string encodeExr(const Image& image, ExrCompression compression = ExrCompression::Rle,
                      ExrLayout layout = ExrLayout::Scanlines, const std::vector<ExrLayer>& layers = {});

}  // namespace photon
