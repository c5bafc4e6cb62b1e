// Shader modules from the SPIR-V embedded at build time, the descriptor set layout, and the
// compute pipelines.
#include "pipelines.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "check.h"
#include "glsl/dispatch.h"
#include "objects.h"
#include "shared/bindings.h"

namespace photon::vk {
namespace spirv {
#include "accumulate.spv.h"
#include "denoise.spv.h"
#include "reproject.spv.h"
#include "gather.spv.h"
#include "gridArgs.spv.h"
#include "gridCount.spv.h"
#include "gridScan.spv.h"
#include "gridScanAdd.spv.h"
#include "gridMerge.spv.h"
#include "gridRank.spv.h"
#include "gridScatter.spv.h"
#include "gridScatterIds.spv.h"
#include "tracePhotons.spv.h"
#include "tracePixels.spv.h"
}  // namespace spirv

namespace {

struct ShaderCode {
    const std::uint32_t* words;
    std::size_t bytes;
};

template <std::size_t N>
ShaderCode code(const std::uint32_t (&words)[N]) {
    return {words, sizeof(words)};
}

constexpr const char* kShaderNames[kShaderCount] = {"tracePhotons", "gridArgs", "gridCount", "gridScan", "gridScanAdd",
                                                   "gridScatter", "gridScatterIds", "gridRank", "gridMerge", "tracePixels", "reproject", "gather", "accumulate", "denoise"};

ShaderCode shaderCode(Shader shader) {
    switch (shader) {
        case kTracePhotons: return code(spirv::tracePhotons);
        case kGridArgs: return code(spirv::gridArgs);
        case kGridCount: return code(spirv::gridCount);
        case kGridScan: return code(spirv::gridScan);
        case kGridScanAdd: return code(spirv::gridScanAdd);
        case kGridScatter: return code(spirv::gridScatter);
        case kGridScatterIds: return code(spirv::gridScatterIds);
        case kGridRank: return code(spirv::gridRank);
        case kGridMerge: return code(spirv::gridMerge);
        case kTracePixels: return code(spirv::tracePixels);
        case kReproject: return code(spirv::reproject);
        case kGather: return code(spirv::gather);
        case kAccumulate: return code(spirv::accumulate);
        case kDenoise: return code(spirv::denoise);
        case kShaderCount: break;
    }
    return {nullptr, 0};
}

// Subgroup size squared: two subgroup scans then cover a workgroup (gridScan.comp handles any
// other size too). A multiple of the largest subgroup size, as full subgroups require.
std::uint32_t chooseScanGroupSize(const Context& context) {
    std::uint32_t s = context.maxSubgroupSize;
    std::uint32_t limit = std::min(context.properties.limits.maxComputeWorkGroupInvocations,
                                   context.properties.limits.maxComputeWorkGroupSize[0]);
    std::uint32_t size = std::min(context.subgroupSize * context.subgroupSize, limit);
    return std::max(s, size / s * s);
}

}  // namespace

GroupCount groupsFor(std::uint64_t items, std::uint32_t groupSize) {
    std::uint64_t groups = (items + groupSize - 1) / groupSize;
    GroupCount count;
    count.x = std::uint32_t(std::min<std::uint64_t>(groups, MAX_GROUPS_X));
    count.y = count.x == 0 ? 0 : std::uint32_t((groups + count.x - 1) / count.x);
    return count;
}

void dispatch(VkCommandBuffer cmd, const Pipelines& pipelines, Shader shader, std::uint64_t items,
              std::uint32_t groupSize) {
    GroupCount groups = groupsFor(items, groupSize);
    if (groups.x == 0) {
        return;
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines.pipeline[shader]);
    vkCmdDispatch(cmd, groups.x, groups.y, 1);
}

Pipelines::Pipelines(const Context& context) : context_(context) {
    VkDevice device = context.device;

    std::vector<VkDescriptorSetLayoutBinding> bindings(BINDING_COUNT);
    for (std::uint32_t b = 0; b < BINDING_COUNT; ++b) {
        bindings[b].binding = b;
        bindings[b].descriptorType =
            b == BINDING_PARAMS ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        bindings[b].descriptorCount = 1;
        bindings[b].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.bindingCount = BINDING_COUNT;
    setInfo.pBindings = bindings.data();
    VK_CHECK(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &setLayout));

    VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, kPushConstantBytes};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &setLayout;
    layoutInfo.pushConstantRangeCount = 1;
    layoutInfo.pPushConstantRanges = &push;
    VK_CHECK(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &layout));

    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, BINDING_COUNT - 1}};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 2;
    poolInfo.pPoolSizes = sizes;
    VK_CHECK(vkCreateDescriptorPool(device, &poolInfo, nullptr, &descriptorPool));
    VkDescriptorSetAllocateInfo allocation{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocation.descriptorPool = descriptorPool;
    allocation.descriptorSetCount = 1;
    allocation.pSetLayouts = &setLayout;
    VK_CHECK(vkAllocateDescriptorSets(device, &allocation, &set));

    // The scan's workgroup size is specialization constant 0; the other shaders fix theirs.
    scanGroupSize = chooseScanGroupSize(context);
    VkSpecializationMapEntry entry{0, 0, sizeof(std::uint32_t)};
    VkSpecializationInfo scanSpecialization{1, &entry, sizeof(std::uint32_t), &scanGroupSize};
    for (std::uint32_t s = 0; s < kShaderCount; ++s) {
        if (s == kGather) {
            continue;
        }
        bool scan = s == kGridScan || s == kGridScanAdd;
        // gridScan numbers its invocations by subgroup, which needs full subgroups.
        VkPipelineShaderStageCreateFlags flags = s == kGridScan ? VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT : 0;
        pipeline[s] = create(Shader(s), scan ? &scanSpecialization : nullptr, flags, kShaderNames[s]);
    }
}

namespace {

// The compiler's statistics of each executable of `pipeline` (VK_KHR_pipeline_executable_properties),
// one line each on stderr.
void printPipelineStatistics(const Context& context, VkPipeline pipeline, const char* name) {
    auto properties = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
        vkGetDeviceProcAddr(context.device, "vkGetPipelineExecutablePropertiesKHR"));
    auto statistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
        vkGetDeviceProcAddr(context.device, "vkGetPipelineExecutableStatisticsKHR"));
    if (properties == nullptr || statistics == nullptr) {
        return;
    }
    VkPipelineInfoKHR info{VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
    info.pipeline = pipeline;
    std::uint32_t count = 0;
    VK_CHECK(properties(context.device, &info, &count, nullptr));
    std::vector<VkPipelineExecutablePropertiesKHR> executables(count, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR});
    VK_CHECK(properties(context.device, &info, &count, executables.data()));
    for (std::uint32_t e = 0; e < count; ++e) {
        VkPipelineExecutableInfoKHR which{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
        which.pipeline = pipeline;
        which.executableIndex = e;
        std::uint32_t n = 0;
        VK_CHECK(statistics(context.device, &which, &n, nullptr));
        std::vector<VkPipelineExecutableStatisticKHR> values(n, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR});
        VK_CHECK(statistics(context.device, &which, &n, values.data()));
        std::string line = std::string("vulkan pipeline ") + name + " (" + executables[e].name + ", subgroup " +
                           std::to_string(executables[e].subgroupSize) + "):";
        for (const VkPipelineExecutableStatisticKHR& v : values) {
            line += std::string(" ") + v.name + " ";
            switch (v.format) {
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: line += v.value.b32 ? "yes" : "no"; break;
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: line += std::to_string(v.value.i64); break;
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR: line += std::to_string(v.value.u64); break;
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR: line += std::to_string(v.value.f64); break;
                default: line += "?"; break;  // a format newer than this code: shown, not guessed
            }
            line += ";";
        }
        std::fprintf(stderr, "%s\n", line.c_str());
    }
}

}  // namespace

VkPipeline createComputePipeline(const Context& context, VkPipelineLayout layout, const std::uint32_t* words,
                                 std::size_t bytes, const char* name, const VkSpecializationInfo* specialization,
                                 VkPipelineShaderStageCreateFlags flags) {
    VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    moduleInfo.codeSize = bytes;
    moduleInfo.pCode = words;
    VkShaderModule module = VK_NULL_HANDLE;
    VK_CHECK(vkCreateShaderModule(context.device, &moduleInfo, nullptr, &module));
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.flags = context.pipelineStatistics ? VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR : 0;
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.flags = flags;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = specialization;
    info.layout = layout;
    VkPipeline created = VK_NULL_HANDLE;
    VkResult result = vkCreateComputePipelines(context.device, VK_NULL_HANDLE, 1, &info, nullptr, &created);
    vkDestroyShaderModule(context.device, module, nullptr);
    VK_CHECK(result);
    if (context.pipelineStatistics) {
        printPipelineStatistics(context, created, name);
    }
    return created;
}

VkPipeline Pipelines::create(Shader shader, const VkSpecializationInfo* specialization,
                             VkPipelineShaderStageCreateFlags flags, const char* name) {
    ShaderCode code = shaderCode(shader);
    return createComputePipeline(context_, layout, code.words, code.bytes, name, specialization, flags);
}

VkPipeline Pipelines::gather(std::uint32_t estimator, std::uint32_t globalMode, bool sppmStart) {
    if (estimator >= ESTIMATOR_COUNT || globalMode >= GLOBAL_MODE_COUNT) {
        throw std::logic_error("Vulkan gather: unknown estimator " + std::to_string(estimator) + " or global mode " +
                               std::to_string(globalMode));
    }
    std::uint32_t variant = (estimator * GLOBAL_MODE_COUNT + globalMode) * 2u + (sppmStart ? 1u : 0u);
    if (gatherVariants_[variant] == VK_NULL_HANDLE) {
        // A specialization constant of type bool is a VkBool32.
        std::uint32_t constants[3] = {estimator, globalMode, sppmStart ? VK_TRUE : VK_FALSE};
        VkSpecializationMapEntry entries[3] = {{1, 0, sizeof(std::uint32_t)},
                                               {2, sizeof(std::uint32_t), sizeof(std::uint32_t)},
                                               {3, 2 * sizeof(std::uint32_t), sizeof(VkBool32)}};
        VkSpecializationInfo specialization{3, entries, sizeof(constants), constants};
        std::string name = std::string("gather<") + std::to_string(estimator) + "," + std::to_string(globalMode) + "," +
                           (sppmStart ? "start" : "steady") + ">";
        gatherVariants_[variant] = create(kGather, &specialization, 0, name.c_str());
    }
    return gatherVariants_[variant];
}

VkPipeline Pipelines::tracing(Shader shader, bool hasMedia) {
    if (shader != kTracePhotons && shader != kTracePixels) {
        throw std::logic_error("Vulkan: only the tracing shaders have a variant without media");
    }
    if (hasMedia) {
        return pipeline[shader];
    }
    VkPipeline& variant = withoutMedia_[shader == kTracePixels ? 1 : 0];
    if (variant == VK_NULL_HANDLE) {
        VkBool32 constant = VK_FALSE;
        VkSpecializationMapEntry entry{4, 0, sizeof(VkBool32)};
        VkSpecializationInfo specialization{1, &entry, sizeof(constant), &constant};
        variant = create(shader, &specialization, 0, shader == kTracePixels ? "tracePixels<no media>" : "tracePhotons<no media>");
    }
    return variant;
}

Pipelines::~Pipelines() {
    VkDevice device = context_.device;
    for (VkPipeline p : pipeline) {
        vkDestroyPipeline(device, p, nullptr);
    }
    for (VkPipeline p : withoutMedia_) {
        vkDestroyPipeline(device, p, nullptr);
    }
    for (VkPipeline p : gatherVariants_) {
        vkDestroyPipeline(device, p, nullptr);
    }
    vkDestroyDescriptorPool(device, descriptorPool, nullptr);
    vkDestroyPipelineLayout(device, layout, nullptr);
    vkDestroyDescriptorSetLayout(device, setLayout, nullptr);
}

void Pipelines::writeDescriptor(std::uint32_t binding, VkBuffer buffer, VkDeviceSize size) {
    VkDescriptorType type = binding == BINDING_PARAMS ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writeBufferDescriptor(context_.device, set, binding, type, buffer, size);
}

}  // namespace photon::vk
