// The viewer's setup, its loop and the summary it prints at exit.
#include "viewer.h"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "core/system/output_file.h"
#include "hud.h"
#include "vulkan/check.h"
#include "vulkan/objects.h"

namespace photon::viewer {

const char* toString(DisplayView view) {
    const char* names[] = {"final", "direct", "global", "caustic", "dots", "grid", "albedo", "normal", "depth", "volume"};
    static_assert(sizeof(names) / sizeof(names[0]) == kDisplayViewCount, "a name for every view");
    if (std::uint32_t(view) >= kDisplayViewCount) {
        throw std::logic_error("unknown display view " + std::to_string(std::uint32_t(view)));
    }
    return names[std::uint32_t(view)];
}

Viewer::Viewer(const ViewerOptions& options)
    : options_(options), camera_(options.scene.camera, options.scene.diagonal()), lights_(options.scene) {
    state_.settings = options.settings;
    state_.view = options.view;
    state_.exposure = options.settings.exposure;
    state_.tonemap = options.settings.tonemap;
    state_.vsync = options.vsync;
    state_.showHud = options.hud;
    state_.screenshotHud = options.screenshotHud;
    scenePath_ = options.scenePath;
    if (!scenePath_.empty()) {
        sceneTime_ = std::filesystem::last_write_time(scenePath_);
    }

    vk::ContextOptions contextOptions;
    contextOptions.device = options.device;
    contextOptions.validation = options.validation;
    contextOptions.graphics = true;
    if (!options.offscreen) {
        window_ = std::make_unique<Window>(options.settings.width, options.settings.height, "photon-view");
        contextOptions.instanceExtensions = Window::requiredInstanceExtensions();
        contextOptions.deviceExtensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
        contextOptions.createSurface = [this](VkInstance instance) { return window_->createSurface(instance); };
    }
    context_ = std::make_shared<vk::Context>(contextOptions);
    {
        auto gpu = std::make_unique<vk::VulkanDevice>(context_);
        gpu_ = gpu.get();
        std::vector<std::unique_ptr<Device>> devices;
        devices.push_back(std::move(gpu));
        renderer_ = std::make_unique<Renderer>(std::move(devices));
    }
    renderer_->setDenoiseEachFrame(true);  // every frame is shown
    choosePhotons(state_.settings, renderer_->runsOnCpu());

    // The display pass leaves a swapchain image ready to present, an offscreen one ready to copy.
    if (window_) {
        swapchain_ = std::make_unique<Swapchain>(*context_);
        display_ = std::make_unique<DisplayPass>(*context_, swapchain_->format().format, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
        swapchain_->create(window_->framebufferSize(), display_->renderPass(), state_.vsync);
    } else {
        display_ = std::make_unique<DisplayPass>(*context_, kOffscreenFormat, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        offscreen_ = std::make_unique<OffscreenTarget>(
            *context_, VkExtent2D{options.settings.width, options.settings.height}, display_->renderPass());
    }
    dots_ = std::make_unique<PhotonDots>(*context_, *gpu_);
    imgui_ = std::make_unique<ImGuiLayer>(*context_, display_->renderPass(), swapchain_ ? swapchain_->imageCount() : 2,
                                          window_ ? window_->handle() : nullptr);
    passTimer_ = std::make_unique<PassTimer>(*context_);
    screenshot_ = std::make_unique<Screenshot>(*context_);
    createFrameResources();

    // The first frame's scene, settings and camera; an impossible request fails here, at start.
    try {
        renderer_->setScene(lights_.scene());
        state_.settingsChanged = true;
        applySettings();
        renderer_->setCamera(camera_.camera());
        renderer_->prepare();
        context_->checkValidation("starting the viewer");
        started_ = true;
    } catch (...) {
        destroyFrameResources();  // the destructor does not run for a constructor that throws
        throw;
    }
    setTitle();
}

void Viewer::setTitle() {
    if (window_) {
        std::string scene = scenePath_.empty() ? renderer_->scene().name : scenePath_;
        window_->setTitle("photon-view: " + scene + " on " + renderer_->deviceName());
    }
}

Viewer::~Viewer() { destroyFrameResources(); }

void Viewer::destroyFrameResources() {
    if (context_) {
        vkDeviceWaitIdle(context_->device);
        vkDestroySemaphore(context_->device, frame_.acquired, nullptr);
        vkDestroyFence(context_->device, frame_.done, nullptr);
        vkDestroyCommandPool(context_->device, frame_.pool, nullptr);
        frame_ = Frame{};
    }
}

void Viewer::createFrameResources() {
    VkDevice device = context_->device;
    vk::CommandBuffer commands = vk::createCommandBuffer(device, context_->queueFamily);
    frame_.pool = commands.pool;
    frame_.cmd = commands.cmd;
    frame_.done = vk::createFence(device);
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VK_CHECK(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &frame_.acquired));
}

VkExtent2D Viewer::targetExtent() const {
    return swapchain_ ? swapchain_->extent() : offscreen_->target().extent;
}

void Viewer::run() {
    auto previous = std::chrono::steady_clock::now();
    lastFinish_ = previous;
    while (keepRunning()) {
        auto now = std::chrono::steady_clock::now();
        float seconds = std::chrono::duration<float>(now - previous).count();
        previous = now;
        // While the GPU runs the previous frame: input and the HUD's widgets for the next.
        imgui_->newFrame(targetExtent(), seconds);
        if (state_.showHud) {
            buildHud(state_, lights_, hudInfo());
        }
        handleInput(seconds);
        // Then the previous frame is done with, and only now may anything change.
        finishFrame();
        animateLight(seconds);
        followCameraPath(seconds);
        applyChanges();
        drawFrame();
    }
    finishFrame();
    printSummary();
}

HudInfo Viewer::hudInfo() const {
    HudInfo info;
    info.device = renderer_->deviceName();
    info.scene = scenePath_.empty() ? renderer_->scene().name : scenePath_;
    info.windowWidth = targetExtent().width;
    info.windowHeight = targetExtent().height;
    VkPresentModeKHR mode = swapchain_ ? swapchain_->presentMode() : VK_PRESENT_MODE_FIFO_KHR;
    info.presentMode = !swapchain_                              ? "offscreen"
                       : mode == VK_PRESENT_MODE_FIFO_KHR    ? "vsync"
                       : mode == VK_PRESENT_MODE_MAILBOX_KHR ? "no vsync (mailbox)"
                                                             : "no vsync (immediate)";
    info.fps = log_.fps();
    info.frame = log_.empty() ? FrameRecord{} : log_.last();
    info.stats = renderer_->lastFrameStats();
    info.accumulated = renderer_->accumulatedFrames();
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        info.radius[m] = renderer_->lastFrameParams().grids[m].radius;
    }
    info.windowed = window_ != nullptr;
    return info;
}

bool Viewer::keepRunning() {
    if (options_.frames > 0 && framesDrawn_ >= options_.frames) {
        return false;
    }
    if (options_.resizeAfter > 0 && framesDrawn_ == options_.resizeAfter && !resizedByScript_) {
        resizedByScript_ = true;
        // Scripted resize: the window (or the offscreen image) takes the new size before the next frame.
        finishFrame();
        if (window_) {
            window_->resize(options_.resizeWidth, options_.resizeHeight);
            swapchainStale_ = true;
        } else {
            offscreen_.reset();
            offscreen_ = std::make_unique<OffscreenTarget>(
                *context_, VkExtent2D{options_.resizeWidth, options_.resizeHeight}, display_->renderPass());
        }
    }
    if (!window_) {
        return true;
    }
    window_->pollEvents();
    if (window_->takeResized()) {
        swapchainStale_ = true;
    }
    // Minimized: nothing to draw into; sleep until the window comes back.
    while (!window_->shouldClose() && window_->minimized()) {
        window_->pollEvents(true);
        swapchainStale_ = true;
    }
    return !window_->shouldClose();
}

void Viewer::printSummary() const {
    if (log_.empty()) {
        return;
    }
    // The first frames build pipelines (LLVM on lavapipe) and grow the photon maps.
    std::size_t skip = log_.size() > 2 ? std::max<std::size_t>(1, log_.size() / 10) : 0;
    FrameRecord m = log_.median(skip);
    const RenderSettings& s = renderer_->settings();
    std::fprintf(stderr, "photon-view: %s, %ux%u %s, %zu frames (median of the last %zu): loop %.2f ms (%.1f fps); GPU ms: ",
                 renderer_->deviceName().c_str(), s.width, s.height, swapchain_ ? "windowed" : "offscreen", log_.size(),
                 log_.size() - skip, m.loopMs, m.loopMs > 0.0 ? 1000.0 / m.loopMs : 0.0);
    for (const StageInfo& stage : kStages) {
        std::fprintf(stderr, "%s %.2f, ", stage.name, m.stages[stage.id]);
    }
    std::fprintf(stderr, "dots %.2f, display %.2f, HUD %.2f; %.1f M photons/s\n", m.passes.dots, m.passes.display,
                 m.passes.hud, m.photonsPerSecond * 1e-6);
    if (options_.statsPath.empty()) {
        return;
    }
    nlohmann::json j;
    j["device"] = renderer_->deviceName();
    j["mode"] = swapchain_ ? "windowed" : "offscreen";
    j["present_mode"] = !swapchain_ ? "none" : swapchain_->presentMode() == VK_PRESENT_MODE_FIFO_KHR ? "fifo" : "no vsync";
    j["width"] = s.width;
    j["height"] = s.height;
    j["photons"] = s.photons;
    j["frames"] = log_.size();
    j["median_of"] = log_.size() - skip;
    j["loop_ms"] = m.loopMs;
    for (const StageInfo& stage : kStages) {
        j["gpu_ms"][stage.name] = m.stages[stage.id];
    }
    j["gpu_ms"]["dots"] = m.passes.dots;
    j["gpu_ms"]["display"] = m.passes.display;
    j["gpu_ms"]["hud"] = m.passes.hud;
    j["gpu_ms"]["total"] = m.stages.total() + m.passes.total();
    j["photons_per_second"] = m.photonsPerSecond;
    writeOutputFile(options_.statsPath, j.dump(2) + "\n", "stats");
}

}  // namespace photon::viewer
