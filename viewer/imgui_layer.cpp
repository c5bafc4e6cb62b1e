#include "imgui_layer.h"

#include <algorithm>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include "core/system/error.h"
#include "vulkan/check.h"
#include "vulkan/memory.h"

namespace photon::viewer {
namespace {

void checkImGuiResult(VkResult result) { VK_CHECK(result); }

}  // namespace

ImGuiLayer::ImGuiLayer(const vk::Context& context, VkRenderPass renderPass, std::uint32_t imageCount,
                       GLFWwindow* window)
    : context_(context) {
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    poolInfo.maxSets = 4;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    VK_CHECK(vkCreateDescriptorPool(context.device, &poolInfo, nullptr, &pool_));

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // no imgui.ini in the working directory
    ImGui::StyleColorsDark();
    ImGui::GetStyle().Alpha = 0.92f;
    if (window != nullptr) {
        glfw_ = ImGui_ImplGlfw_InitForVulkan(window, true);
        if (!glfw_) {
            throw RuntimeError("Dear ImGui: the GLFW backend failed to start");
        }
    }
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = context.instance;
    info.PhysicalDevice = context.physicalDevice;
    info.Device = context.device;
    info.QueueFamily = context.queueFamily;
    info.Queue = context.queue;
    info.DescriptorPool = pool_;
    info.Subpass = 0;
    info.MinImageCount = std::max(imageCount, 2u);
    info.ImageCount = std::max(imageCount, 2u);
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = checkImGuiResult;
    if (!ImGui_ImplVulkan_Init(&info, renderPass)) {
        throw RuntimeError("Dear ImGui: the Vulkan backend failed to start");
    }
    uploadFonts();
}

ImGuiLayer::~ImGuiLayer() {
    vkDeviceWaitIdle(context_.device);
    ImGui_ImplVulkan_Shutdown();
    if (glfw_) {
        ImGui_ImplGlfw_Shutdown();
    }
    ImGui::DestroyContext();
    vkDestroyDescriptorPool(context_.device, pool_, nullptr);
}

// The font atlas goes to the device once, through the backend's one-off transfers.
void ImGuiLayer::uploadFonts() {
    vk::Transfers transfers(context_);
    transfers.run([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

void ImGuiLayer::newFrame(VkExtent2D size, float seconds) {
    ImGui_ImplVulkan_NewFrame();
    if (glfw_) {
        ImGui_ImplGlfw_NewFrame();
    } else {
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(float(size.width), float(size.height));
        io.DeltaTime = seconds > 0.0f ? seconds : 1.0f / 60.0f;
    }
    ImGui::NewFrame();
}

void ImGuiLayer::render(VkCommandBuffer cmd, bool draw) {
    ImGui::Render();
    if (draw) {
        ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    }
}

bool ImGuiLayer::wantsMouse() const { return ImGui::GetIO().WantCaptureMouse; }

bool ImGuiLayer::typing() const { return ImGui::GetIO().WantTextInput; }

}  // namespace photon::viewer
