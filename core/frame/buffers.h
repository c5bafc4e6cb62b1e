// How large every buffer of shared/bindings.h is for a scene, a photon budget and an image, and
// whether that fits the machine: one plan that every backend allocates from and checks against
// its own limits before any work starts.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "core/frame/frame_setup.h"
#include "core/scene/scene.h"
#include "shared/bindings.h"

namespace photon {

struct BufferPlan {
    std::uint64_t elements[BINDING_COUNT] = {};  // by binding; the parameters are one FrameParams
    std::uint64_t scratchBytes = 0;              // a backend's own working memory besides the buffers
                                                 // (Renderer::adjustPlan: scan and sort storage)

    std::uint64_t bytes(std::uint32_t binding) const;
    std::uint64_t totalBytes() const;
};

BufferPlan planBuffers(const Scene& scene, const PhotonBudget& budget, std::uint32_t width, std::uint32_t height);

// The plan of a device that only runs the photon pass (one of several but the first:
// core/frame/collective.h): the scene, the parameters, the photons and the counters as planned,
// every other buffer one element.
void keepPhotonPassBuffers(BufferPlan& plan);

// Resizes the buffers (not the scene's) whose size the plan changes: `holds(binding, bytes)` says
// whether the backend's buffer at `binding` already fits `bytes`; `resize(binding, bytes)` frees
// it (bytes 0) or allocates it zeroed. Buffers whose size is unchanged are kept (a grown photon
// map keeps the accumulated image); the others are all freed before any is allocated, so that old
// and new need not fit together.
void resizeChangedBuffers(const BufferPlan& plan, const std::function<bool(std::uint32_t, std::uint64_t)>& holds,
                          const std::function<void(std::uint32_t, std::uint64_t)>& resize);

// Calls upload(binding, data, bytes) for each scene array (size class SCENE), `bytes` as the plan
// sizes its buffer: the array itself, or one zeroed element when it is empty.
void forEachSceneBuffer(const Scene& scene, const BufferPlan& plan,
                        const std::function<void(std::uint32_t, const void*, std::uint64_t)>& upload);

// What a backend may allocate: all buffers together, and one buffer alone.
struct MemoryLimits {
    std::string device;           // for messages: "NVIDIA H200", "llvmpipe", "this machine"
    std::string memory;           // "device memory", "physical memory"
    std::uint64_t total = 0;      // bytes all buffers may take
    std::uint64_t perBuffer = 0;  // bytes one buffer may take (0: no limit of its own)
    std::string perBufferLimit;   // its name, e.g. "maxStorageBufferRange"
};

// Throws InputError naming the buffer, its size, the limit and the setting to lower when the plan
// does not fit.
void checkMemory(const BufferPlan& plan, const MemoryLimits& limits, std::uint32_t width, std::uint32_t height);

// Host memory this process may still take: what the OS reports available, or less under an
// address-space limit (ulimit -v).
std::uint64_t availableHostMemory();

// Host memory an image takes besides the backend's buffers: its readback and its encoding.
inline constexpr std::uint64_t kHostBytesPerPixel = 24;
// ... and a render's images together, a pixel: the image, the one before the denoiser beside it
// (`denoise`), and with `aov` the auxiliary buffer's readback and its four images (aov_images.h).
std::uint64_t hostBytesPerPixel(bool denoise, bool aov);

// The setting that shrinks buffers of a BUFFER_PER_* class, for messages.
const char* whatToLower(std::uint32_t sizeClass);
// ... for one buffer: its class's, but a scene array that one key sizes names it (the media's
// density voxels: their grids' resolution).
const char* whatToLowerFor(std::uint32_t binding);

std::string formatMiB(std::uint64_t bytes);

}  // namespace photon
