// photon-bench's CUDA-only measurements, next to the timing table's: launch shapes
// (--launch-sweep), image readback (--readback) and primary rays alone (--primary-rays). Without
// the CUDA backend (PHOTON_HAVE_CUDA) they do nothing.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "core/frame/renderer.h"

namespace photon {

// Runs `measure` once per CUDA launch shape (threads per photon block; one pixel tile for the eye
// pass and every other per-pixel stage, each of which the table times apart) after the backend's own
// configuration ("default"), then once per other register cap of the sppm gather.
// Each shape starts from the backend's own configuration (its gridBlocks follow the device's SMs).
void sweepLaunchShapes(Renderer& backend, const std::function<void(const std::string&)>& measure);

// Median host time of Renderer::image() (a synchronous copy of the accumulated image), through
// pinned memory and straight into pageable memory.
void timeReadback(Renderer& backend);

// Times primary rays alone (nearest hit, no shading) of the backend's current frame, prints the
// median of 21 and returns rays per second (0 without CUDA).
double timePrimaryRays(Renderer& backend, std::uint32_t width, std::uint32_t height);

}  // namespace photon
