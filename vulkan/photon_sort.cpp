#include "photon_sort.h"

#include <algorithm>

#include "check.h"
#include "glsl/dispatch.h"
#include "glsl/sort.h"
#include "objects.h"
#include "shared/bindings.h"
#include "shared/photon_map.h"

namespace photon::vk {
namespace spirv {
#include "sortArgs.spv.h"
#include "sortCount.spv.h"
#include "sortKeys.spv.h"
#include "sortPlace.spv.h"
#include "sortScan.spv.h"
#include "sortScatter.spv.h"
}  // namespace spirv

namespace {

std::uint64_t tilesFor(std::uint32_t capacity) { return std::max<std::uint64_t>(1, (std::uint64_t(capacity) + SORT_TILE - 1) / SORT_TILE); }

// Each barrier of the sort orders all compute writes before all later compute (and indirect) reads.
void computeBarrier(VkCommandBuffer cmd) {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
}

}  // namespace

PhotonSort::PhotonSort(const Context& context, const Pipelines& pipelines) : context_(context), backend_(pipelines) {
    VkDevice device = context.device;
    VkDescriptorSetLayoutBinding bindings[SORT_BINDING_COUNT] = {};
    for (std::uint32_t b = 0; b < SORT_BINDING_COUNT; ++b) {
        bindings[b] = {b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    }
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.bindingCount = SORT_BINDING_COUNT;
    setInfo.pBindings = bindings;
    VK_CHECK(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &setLayout_));
    VkDescriptorSetLayout sets[2] = {pipelines.setLayout, setLayout_};
    // The backend's push-constant range, so that its set 0 stays bound across the sort.
    static_assert(sizeof(SortPush) <= kPushConstantBytes, "the sort's push constants fit the backend's range");
    layout_ = createPipelineLayout(device, sets, 2, {VK_SHADER_STAGE_COMPUTE_BIT, 0, kPushConstantBytes});
    SingleDescriptorSet descriptors = allocateSingleSet(device, setLayout_, SORT_BINDING_COUNT);
    pool_ = descriptors.pool;
    set_ = descriptors.set;

    auto create = [&](const auto& words, const char* name, VkPipelineShaderStageCreateFlags flags = 0) {
        return createComputePipeline(context, layout_, words, sizeof(words), name, nullptr, flags);
    };
    pipelines_[kArgs] = create(spirv::sortArgs, "sortArgs");
    pipelines_[kKeys] = create(spirv::sortKeys, "sortKeys");
    pipelines_[kCount] = create(spirv::sortCount, "sortCount");
    pipelines_[kScan] = create(spirv::sortScan, "sortScan");
    // sortScatter numbers its invocations by subgroup, which needs full subgroups.
    pipelines_[kScatter] = create(spirv::sortScatter, "sortScatter", VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT);
    pipelines_[kPlace] = create(spirv::sortPlace, "sortPlace");
}

PhotonSort::~PhotonSort() {
    VkDevice device = context_.device;
    vkDeviceWaitIdle(device);
    for (VkPipeline p : pipelines_) {
        vkDestroyPipeline(device, p, nullptr);
    }
    vkDestroyPipelineLayout(device, layout_, nullptr);
    vkDestroyDescriptorPool(device, pool_, nullptr);
    vkDestroyDescriptorSetLayout(device, setLayout_, nullptr);
}

VkDeviceSize PhotonSort::largestBufferFor(std::uint32_t capacity) {
    return VkDeviceSize(std::max<std::uint32_t>(capacity, 1)) * 2 * sizeof(glm::uvec2);
}

VkDeviceSize PhotonSort::bytesFor(std::uint32_t capacity) {
    VkDeviceSize elements = std::max<std::uint32_t>(capacity, 1);
    return elements * 2 * (sizeof(glm::uvec2) + sizeof(std::uint32_t)) + tilesFor(capacity) * SORT_BINS * sizeof(std::uint32_t) +
           SORT_STATE_WORDS * sizeof(std::uint32_t);
}

void PhotonSort::reserve(std::uint32_t capacity) {
    capacity = std::max<std::uint32_t>(capacity, 1);
    if (capacity <= capacity_) {
        return;
    }
    VK_CHECK(vkQueueWaitIdle(context_.queue));  // nothing may still use the old buffers
    VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    keys_ = Buffer();
    values_ = Buffer();
    histograms_ = Buffer();
    keys_ = Buffer(context_, VkDeviceSize(capacity) * 2 * sizeof(glm::uvec2), storage, MemoryUse::Device);
    values_ = Buffer(context_, VkDeviceSize(capacity) * 2 * sizeof(std::uint32_t), storage, MemoryUse::Device);
    histograms_ = Buffer(context_, tilesFor(capacity) * SORT_BINS * sizeof(std::uint32_t), storage, MemoryUse::Device);
    if (state_.handle() == VK_NULL_HANDLE) {
        state_ = Buffer(context_, SORT_STATE_WORDS * sizeof(std::uint32_t), storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                        MemoryUse::Device);
    }
    const Buffer* buffers[SORT_BINDING_COUNT] = {&keys_, &values_, &histograms_, &state_};
    for (std::uint32_t b = 0; b < SORT_BINDING_COUNT; ++b) {
        writeBufferDescriptor(context_.device, set_, b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, buffers[b]->handle(),
                              buffers[b]->size());
    }
    capacity_ = capacity;
}

void PhotonSort::record(VkCommandBuffer cmd, const FrameParams& params, std::uint32_t map, VkBuffer cellCounts) {
    const GridParams& grid = params.grids[map];
    VkDescriptorSet sets[2] = {backend_.set, set_};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 2, sets, 0, nullptr);
    VkBuffer state = state_.handle();
    auto run = [&](SortShader shader, const SortPush& push, VkDeviceSize indirectWord) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_[shader]);
        vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
        if (indirectWord == ~VkDeviceSize(0)) {
            vkCmdDispatch(cmd, 1, 1, 1);
        } else {
            vkCmdDispatchIndirect(cmd, state, indirectWord * sizeof(std::uint32_t));
        }
        computeBarrier(cmd);
    };
    constexpr VkDeviceSize kOneGroup = ~VkDeviceSize(0);

    // The previous map's sort is done with the state and histograms before this one rewrites them.
    computeBarrier(cmd);
    run(kArgs, {map, 0, 0, 0}, kOneGroup);
    run(kKeys, {map, 0, 0, 0}, SORT_STATE_ELEMENT_ARGS);
    std::uint32_t bits = photonSortKeyBits(params, map);
    std::uint32_t source = 0;
    for (std::uint32_t shift = 0; shift < bits; shift += SORT_DIGIT_BITS) {
        std::uint32_t target = capacity_ - source;  // the other half
        SortPush push{map, shift, source, target};
        run(kCount, push, SORT_STATE_TILE_ARGS);
        run(kScan, push, kOneGroup);
        run(kScatter, push, SORT_STATE_TILE_ARGS);
        source = target;
    }
    run(kPlace, {map, 0, source, 0}, SORT_STATE_ELEMENT_ARGS);

    // The scatter would have left the counts at zero for the next frame: clear them instead, once
    // the count step's atomics and the scan's reads are done (they were, at the first barrier).
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdFillBuffer(cmd, cellCounts, VkDeviceSize(grid.cellOffset) * sizeof(std::uint32_t),
                    VkDeviceSize(grid.cellCount + 1) * sizeof(std::uint32_t), 0u);
    // The cleared counts are in place before any later compute shader (next frame's count step).
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

}  // namespace photon::vk
