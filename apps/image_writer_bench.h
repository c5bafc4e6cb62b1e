// photon-bench --image-writers: the time to write each image format (and each EXR compression) of
// one rendered frame, at each resolution.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/frame/renderer.h"

namespace photon {

// Renders `scene` one frame at each resolution on `backend`, then encodes and writes each format
// `writes` times into `folder` (after one untimed write) and prints a table: format, compression,
// resolution, file size, and medians of the encoding alone and of the whole file (encoding,
// then core/system/output_file.h's atomic write: temporary file, flush to disk, rename). The files
// are removed at the end.
void benchImageWriters(Renderer& backend, const Scene& scene,
                       const std::vector<std::pair<std::uint32_t, std::uint32_t>>& resolutions, std::uint32_t writes,
                       const std::string& folder);

}  // namespace photon
