// photon-view: the Vulkan backend driven frame by frame, shown in a window (or drawn offscreen),
// with a free camera, the HUD and screenshots.
//
// One frame is one command buffer and one submission: the Renderer's stages on its one Vulkan
// device, recorded into the viewer's command buffer (Renderer::recordFrame, through
// VulkanDevice::recordInto: the same stage loop as every other program), the photon dots if shown, then one render pass that tone-maps the
// accumulation into the target image and draws the HUD over it. One frame is in flight: while the
// GPU runs frame N, the CPU polls input and builds the HUD for N + 1, then waits for N, hands its
// stats to the renderer (Renderer::endFrame) and only then applies what changed, so that a reset
// never meets a frame that is still running.
//
//   viewer.cpp        setup, the loop, exit summary
//   viewer_frame.cpp  recording, submitting and finishing a frame
//   viewer_state.cpp  applying the ViewState to the backend; opening and reloading scenes
//   viewer_input.cpp  mouse and keys
#pragma once

#include <chrono>
#include <filesystem>
#include <future>
#include <memory>
#include <string>

#include "camera_controller.h"
#include "display_pass.h"
#include "frame_log.h"
#include "hud.h"
#include "imgui_layer.h"
#include "light_editor.h"
#include "offscreen.h"
#include "options.h"
#include "photon_dots.h"
#include "screenshot.h"
#include "state.h"
#include "swapchain.h"
#include "vulkan/device.h"
#include "window.h"

namespace photon::viewer {

class Viewer : vk::NonCopyable {
public:
    explicit Viewer(const ViewerOptions& options);
    ~Viewer();

    // Runs until the window closes (or the scripted frames are done). Throws on failure.
    void run();

private:
    // viewer.cpp
    void createFrameResources();
    void destroyFrameResources();
    void setTitle();
    bool keepRunning();
    void printSummary() const;
    VkExtent2D targetExtent() const;
    HudInfo hudInfo() const;

    // viewer_frame.cpp
    void drawFrame();
    void finishFrame();
    void recreateSwapchain();

    // viewer_state.cpp
    void applyChanges();
    void applySettings();
    void loadScene(const std::string& path, bool keepCameraAndSettings);
    void finishLoadingScene();
    void installScene(const Scene& scene, const std::string& path, bool keepCameraAndSettings);
    void report(const std::string& message);
    void watchSceneFile();
    void animateLight(float seconds);
    void followCameraPath(float seconds);

    // viewer_input.cpp
    void handleInput(float seconds);
    void handleKey(int key);

    ViewerOptions options_;
    ViewState state_;

    // Declared in the order they are built; destroyed in reverse, the window last.
    std::unique_ptr<Window> window_;                 // none offscreen
    std::shared_ptr<vk::Context> context_;
    std::unique_ptr<Renderer> renderer_;
    vk::VulkanDevice* gpu_ = nullptr;                // the renderer's one device
    std::unique_ptr<DisplayPass> display_;
    std::unique_ptr<Swapchain> swapchain_;           // windowed
    std::unique_ptr<OffscreenTarget> offscreen_;     // offscreen
    std::unique_ptr<PhotonDots> dots_;
    std::unique_ptr<ImGuiLayer> imgui_;
    std::unique_ptr<PassTimer> passTimer_;
    std::unique_ptr<Screenshot> screenshot_;

    // The one frame in flight.
    struct Frame {
        VkCommandPool pool = VK_NULL_HANDLE;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence done = VK_NULL_HANDLE;           // signalled when its commands have run
        VkSemaphore acquired = VK_NULL_HANDLE;   // the swapchain image is ready to be drawn
        bool pending = false;                    // submitted and not yet finished
        std::string screenshot;                  // its commands copy the target, to be saved here
    } frame_;

    CameraController camera_;
    LightEditor lights_;
    RenderSettings goodSettings_;          // the last settings the backend accepted
    std::string scenePath_;                // empty: the built-in Cornell box
    std::future<Scene> loading_;           // a scene file being read and parsed, if any
    std::string loadingPath_;
    bool loadingKeeps_ = false;            // it keeps the camera and settings (a reload)
    std::filesystem::file_time_type sceneTime_{};
    std::chrono::steady_clock::time_point lastWatch_{};
    glm::vec3 lightCircleCentre_{0.0f};    // where the circling light started
    float lightCircleAngle_ = -1.0f;      // negative: not circling
    double pathSeconds_ = 0.0;             // how far along --camera-path the camera is
    bool swapchainStale_ = false;          // recreate before the next frame
    bool resizedByScript_ = false;         // --resize-after has happened
    bool started_ = false;                 // the first settings were accepted
    bool dragging_ = false;                // a mouse drag that began outside the HUD
    glm::dvec2 cursor_{0.0};
    std::uint32_t framesDrawn_ = 0;
    std::uint32_t screenshotCount_ = 0;
    std::chrono::steady_clock::time_point lastFinish_{};
    FrameLog log_;
};

}  // namespace photon::viewer
