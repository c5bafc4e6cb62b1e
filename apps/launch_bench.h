// photon-bench's measurements of the GPU backends' launches, next to the timing table's: launch
// shapes (--launch-sweep; CUDA and Vulkan), and on CUDA image readback (--readback) and primary
// rays alone (--primary-rays). Without the backend (PHOTON_HAVE_CUDA, PHOTON_HAVE_VULKAN) they do
// nothing.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "core/frame/renderer.h"

namespace photon {

// Runs `measure` once per launch shape of the backend's device: on CUDA threads per photon block
// and pixel tile, then the sppm gather's pool (pixel tiles a block, 0: none); on Vulkan the sppm
// gather's pool. Each shape starts from the device's own configuration (CUDA's gridBlocks follow
// the device's SMs), which is restored at the end.
void sweepLaunchShapes(Renderer& backend, const std::function<void(const std::string&)>& measure);

// The sppm gather's pool of the backend's GPU device: pixel tiles a block or workgroup, 0 for
// one thread a pixel, at most kMaxGatherPool (nothing on the CPU).
constexpr std::uint32_t kMaxGatherPool = 64;
void setGatherPool(Renderer& backend, std::uint32_t tiles);

// Median host time of Renderer::image() (a synchronous copy of the accumulated image), through
// pinned memory and straight into pageable memory.
void timeReadback(Renderer& backend);

// Times primary rays alone (nearest hit, no shading) of the backend's current frame, prints the
// median of 21 and returns rays per second (0 without CUDA).
double timePrimaryRays(Renderer& backend, std::uint32_t width, std::uint32_t height);

}  // namespace photon
