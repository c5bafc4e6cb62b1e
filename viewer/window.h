// The GLFW window: creation, the Vulkan surface, and the input the viewer reads each frame
// (events queued by callbacks, held keys and buttons polled). GLFW is initialised here and only
// here, so the offscreen viewer never touches a display.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vulkan/non_copyable.h"

struct GLFWwindow;

namespace photon::viewer {

struct KeyPress {
    int key = 0;   // GLFW_KEY_*
    int mods = 0;  // GLFW_MOD_*
};

class Window : vk::NonCopyable {
public:
    Window(std::uint32_t width, std::uint32_t height, const std::string& title);
    ~Window();

    // VK_KHR_surface and the window system's surface extension.
    static std::vector<const char*> requiredInstanceExtensions();
    VkSurfaceKHR createSurface(VkInstance instance);

    GLFWwindow* handle() const { return window_; }
    bool shouldClose() const;
    void requestClose();
    void setTitle(const std::string& title);
    // Resizes the window and waits (up to two seconds) until the window system has done it.
    void resize(std::uint32_t width, std::uint32_t height);

    // The framebuffer's size in pixels; 0 × 0 while minimized on some systems.
    VkExtent2D framebufferSize() const;
    // Iconified, or of no size: nothing to draw (and presenting may block).
    bool minimized() const;
    // Polls events; `wait`: sleeps until one arrives (while minimized).
    void pollEvents(bool wait = false);

    // Input since the last call of each, then cleared.
    std::vector<KeyPress> takeKeyPresses();
    float takeScroll();
    std::vector<std::string> takeDroppedPaths();
    bool takeResized();  // the framebuffer changed size

    // Held state, read when asked.
    bool keyDown(int key) const;
    bool buttonDown(int button) const;
    double cursorX() const;
    double cursorY() const;

private:
    static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
    static void onScroll(GLFWwindow* window, double dx, double dy);
    static void onDrop(GLFWwindow* window, int count, const char** paths);
    static void onFramebufferSize(GLFWwindow* window, int width, int height);

    GLFWwindow* window_ = nullptr;
    std::vector<KeyPress> keys_;
    float scroll_ = 0.0f;
    std::vector<std::string> dropped_;
    bool resized_ = false;
};

}  // namespace photon::viewer
