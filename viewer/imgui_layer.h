// Dear ImGui on the viewer's device: the context, the GLFW platform backend (windowed only: the
// offscreen viewer feeds size and time itself), the Vulkan renderer backend in the display pass's
// render pass, and the font upload. The panel itself is hud.cpp.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "vulkan/context.h"
#include "vulkan/non_copyable.h"

struct GLFWwindow;

namespace photon::viewer {

class ImGuiLayer : vk::NonCopyable {
public:
    // `window` may be null (offscreen). `imageCount`: images the draw data may be in flight for.
    ImGuiLayer(const vk::Context& context, VkRenderPass renderPass, std::uint32_t imageCount, GLFWwindow* window);
    ~ImGuiLayer();

    // Starts a frame of widgets for a display of `size` pixels, `seconds` after the last.
    void newFrame(VkExtent2D size, float seconds);
    // Ends the frame of widgets; draws them into the render pass begun in `cmd` if `draw`.
    void render(VkCommandBuffer cmd, bool draw);

    // The pointer is over the HUD (or dragging one of its widgets).
    bool wantsMouse() const;
    // A text field of the HUD is being typed in: keys are not shortcuts then. (Not Dear ImGui's
    // WantCaptureKeyboard, which also holds while a slider is held, and would drop keys pressed
    // during a long frame on a slow device.)
    bool typing() const;

private:
    void uploadFonts();

    const vk::Context& context_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;  // the font texture's descriptor set
    bool glfw_ = false;
};

}  // namespace photon::viewer
