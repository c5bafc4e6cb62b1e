#include "window.h"

#include <chrono>
#include <string>
#include <utility>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "core/system/error.h"
#include "vulkan/check.h"

namespace photon::viewer {
namespace {

void onGlfwError(int code, const char* description) {
    (void)code;
    (void)description;  // glfwInit and glfwCreateWindow failures are reported where they happen
}

Window* self(GLFWwindow* window) { return static_cast<Window*>(glfwGetWindowUserPointer(window)); }

std::string lastGlfwError() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "unknown error";
}

}  // namespace

Window::Window(std::uint32_t width, std::uint32_t height, const std::string& title) {
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit()) {
        throw RuntimeError("cannot open a window (" + lastGlfwError() +
                           "); without a display, run under xvfb-run or use --offscreen");
    }
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        throw RuntimeError("GLFW finds no Vulkan loader");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    if (window_ == nullptr) {
        std::string error = lastGlfwError();
        glfwTerminate();
        throw RuntimeError("cannot create a " + std::to_string(width) + "x" + std::to_string(height) +
                           " window: " + error);
    }
    glfwSetWindowUserPointer(window_, this);
    // Installed before Dear ImGui's, which call these after their own.
    glfwSetKeyCallback(window_, onKey);
    glfwSetScrollCallback(window_, onScroll);
    glfwSetDropCallback(window_, onDrop);
    glfwSetFramebufferSizeCallback(window_, onFramebufferSize);
}

Window::~Window() {
    glfwDestroyWindow(window_);
    glfwTerminate();
}

std::vector<const char*> Window::requiredInstanceExtensions() {
    std::uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (names == nullptr) {
        throw RuntimeError("GLFW cannot present with Vulkan here: " + lastGlfwError());
    }
    return std::vector<const char*>(names, names + count);
}

VkSurfaceKHR Window::createSurface(VkInstance instance) {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VK_CHECK(glfwCreateWindowSurface(instance, window_, nullptr, &surface));
    return surface;
}

bool Window::shouldClose() const { return glfwWindowShouldClose(window_) != 0; }

void Window::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

void Window::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

void Window::resize(std::uint32_t width, std::uint32_t height) {
    glfwSetWindowSize(window_, int(width), int(height));
    auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (std::chrono::steady_clock::now() < deadline) {
        VkExtent2D size = framebufferSize();
        if (size.width == width && size.height == height) {
            break;
        }
        glfwWaitEventsTimeout(0.01);
    }
    resized_ = true;
}

VkExtent2D Window::framebufferSize() const {
    int width = 0;
    int height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    return {std::uint32_t(width), std::uint32_t(height)};
}

bool Window::minimized() const {
    VkExtent2D size = framebufferSize();
    return glfwGetWindowAttrib(window_, GLFW_ICONIFIED) != 0 || size.width == 0 || size.height == 0;
}

void Window::pollEvents(bool wait) {
    if (wait) {
        glfwWaitEvents();
    } else {
        glfwPollEvents();
    }
}

std::vector<KeyPress> Window::takeKeyPresses() { return std::exchange(keys_, {}); }

float Window::takeScroll() { return std::exchange(scroll_, 0.0f); }

std::vector<std::string> Window::takeDroppedPaths() { return std::exchange(dropped_, {}); }

bool Window::takeResized() { return std::exchange(resized_, false); }

bool Window::keyDown(int key) const { return glfwGetKey(window_, key) == GLFW_PRESS; }

bool Window::buttonDown(int button) const { return glfwGetMouseButton(window_, button) == GLFW_PRESS; }

double Window::cursorX() const {
    double x = 0.0;
    double y = 0.0;
    glfwGetCursorPos(window_, &x, &y);
    return x;
}

double Window::cursorY() const {
    double x = 0.0;
    double y = 0.0;
    glfwGetCursorPos(window_, &x, &y);
    return y;
}

void Window::onKey(GLFWwindow* window, int key, int, int action, int mods) {
    if (action == GLFW_PRESS || action == GLFW_REPEAT) {
        self(window)->keys_.push_back({key, mods});
    }
}

void Window::onScroll(GLFWwindow* window, double, double dy) { self(window)->scroll_ += float(dy); }

void Window::onDrop(GLFWwindow* window, int count, const char** paths) {
    for (int i = 0; i < count; ++i) {
        self(window)->dropped_.emplace_back(paths[i]);
    }
}

void Window::onFramebufferSize(GLFWwindow* window, int, int) { self(window)->resized_ = true; }

}  // namespace photon::viewer
