// The Vulkan backend's deterministic grid build: after the count step and the scan, the photons of
// a map sorted by (cell key, photon id) with the radix sort of glsl/sort.h, which replaces the
// scatter and gives every cell its photons in canonical order (shared/photon_map.h).
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "context.h"
#include "memory.h"
#include "pipelines.h"
#include "shared/layout.h"

namespace photon::vk {

class PhotonSort {
public:
    PhotonSort(const Context& context, const Pipelines& pipelines);
    ~PhotonSort();
    PhotonSort(const PhotonSort&) = delete;
    PhotonSort& operator=(const PhotonSort&) = delete;

    // Bytes of the sort's buffers for maps of up to `capacity` photons, and the largest of them.
    static VkDeviceSize bytesFor(std::uint32_t capacity);
    static VkDeviceSize largestBufferFor(std::uint32_t capacity);

    // Room for maps of up to `capacity` photons (buffers are kept if large enough).
    void reserve(std::uint32_t capacity);

    // Records map `map`'s sort into sortedPhotons, then clears its cell counts. The counts, keys
    // and cell starts must be written (and visible to compute shaders) before; the photon map is
    // visible to compute shaders after.
    void record(VkCommandBuffer cmd, const FrameParams& params, std::uint32_t map, VkBuffer cellCounts);

private:
    enum SortShader { kArgs, kKeys, kCount, kScan, kScatter, kPlace, kSortShaderCount };

    const Context& context_;
    const Pipelines& backend_;                        // set 0: the backend's buffers
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;  // set 1: the sort's own buffers
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    VkPipeline pipelines_[kSortShaderCount] = {};
    Buffer keys_;        // two arrays of `capacity_` uvec2 keys: a pass reads one, writes the other
    Buffer values_;      // likewise, photon indices
    Buffer histograms_;  // SORT_BINS counts per tile
    Buffer state_;       // SORT_STATE_* words
    std::uint32_t capacity_ = 0;
};

}  // namespace photon::vk
