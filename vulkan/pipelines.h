// The compute pipelines, one per shader of glsl/, all over one pipeline layout: one descriptor set
// holding every buffer of shared/bindings.h, and a few words of push constants. Built once.
#pragma once

#include <cstddef>
#include <cstdint>

#include <vulkan/vulkan.h>

#include "context.h"
#include "shared/constants.h"

namespace photon::vk {

enum Shader : std::uint32_t {
    kTracePhotons,  // STAGE_TRACE_PHOTONS
    kGridArgs,      // STAGE_BUILD_GRID: group counts of the count and scatter passes
    kGridCount,     //   cell keys and photons per cell
    kGridScan,      //   one level of the exclusive scan of the counts
    kGridScanAdd,   //   adds the scanned block totals back down a level
    kGridScatter,   //   photons into cell order
    kGridScatterIds,  //   or, for deterministic maps, (id, index) pairs into cell order,
    kGridRank,        //   each ranked within its chunk of the cell,
    kGridMerge,       //   and the chunks of the larger cells merged
    kTracePixels,   // STAGE_TRACE_PIXELS
    kReproject,     // STAGE_REPROJECT, a pass at a time
    kGather,        // STAGE_GATHER
    kAccumulate,    // STAGE_ACCUMULATE
    kDenoise,       // STAGE_DENOISE, a pass at a time
    kShaderCount
};

constexpr std::uint32_t kPushConstantBytes = 32;

// Workgroups for `items` invocations in groups of `groupSize`, wrapped into y beyond
// MAX_GROUPS_X groups as the shaders expect (glsl/dispatch.h).
struct GroupCount {
    std::uint32_t x = 0;
    std::uint32_t y = 0;
};
GroupCount groupsFor(std::uint64_t items, std::uint32_t groupSize);

// A compute pipeline from SPIR-V words (`bytes` long) over `layout`. With the context's
// pipelineStatistics, its compiler statistics are printed under `name`.
VkPipeline createComputePipeline(const Context& context, VkPipelineLayout layout, const std::uint32_t* words,
                                 std::size_t bytes, const char* name, const VkSpecializationInfo* specialization = nullptr,
                                 VkPipelineShaderStageCreateFlags flags = 0);

// Binds `shader` and dispatches `items` invocations (rounded up to whole workgroups).
void dispatch(VkCommandBuffer cmd, const class Pipelines& pipelines, Shader shader, std::uint64_t items,
              std::uint32_t groupSize);

class Pipelines : NonCopyable {
public:
    explicit Pipelines(const Context& context);
    ~Pipelines();

    // Points binding `binding` of the descriptor set at a whole buffer. Only between frames.
    void writeDescriptor(std::uint32_t binding, VkBuffer buffer, VkDeviceSize size);

    // The gather pipeline specialized for an ESTIMATOR_*, a GLOBAL_* mode and whether the frame
    // starts sppm (sppmStarts), built on first use.
    VkPipeline gather(std::uint32_t estimator, std::uint32_t globalMode, bool sppmStart);
    // kTracePhotons or kTracePixels for a frame: for scenes without media (hasMedia false), the
    // pipeline specialized without their code (SCENE_HAS_MEDIA, shared/medium.h), built on first use.
    VkPipeline tracing(Shader shader, bool hasMedia);

    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;  // BINDING_COUNT buffers: params uniform, the rest storage
    VkPipelineLayout layout = VK_NULL_HANDLE;          // the set, then kPushConstantBytes of push constants
    VkDescriptorPool descriptorPool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;              // the one set every dispatch uses
    VkPipeline pipeline[kShaderCount] = {};            // by Shader; kGather: see gather()
    std::uint32_t scanGroupSize = 0;                   // workgroup of gridScan/gridScanAdd: subgroup size²,
                                                       // within the device's limits

private:
    VkPipeline create(Shader shader, const VkSpecializationInfo* specialization, VkPipelineShaderStageCreateFlags flags,
                      const char* name);

    const Context& context_;
    static constexpr std::uint32_t kGatherVariants = ESTIMATOR_COUNT * GLOBAL_MODE_COUNT * 2;
    VkPipeline gatherVariants_[kGatherVariants] = {};
    VkPipeline withoutMedia_[2] = {};  // tracePhotons, tracePixels
};

}  // namespace photon::vk
