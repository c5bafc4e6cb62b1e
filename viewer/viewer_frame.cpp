// One frame: the backend's stages, the photon dots, the display pass with the HUD, an optional
// screenshot copy, in one command buffer; then, once it has run, its stats and screenshot.
#include "viewer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "vulkan/check.h"

namespace photon::viewer {
namespace {

// The next photon-view-N.png that does not exist yet in the working directory.
std::string nextScreenshotPath(std::uint32_t& count) {
    for (;; ++count) {
        std::string path = "photon-view-" + std::to_string(count) + ".png";
        if (!std::filesystem::exists(path)) {
            return path;
        }
    }
}

// The power of a global photon as emitted: the lights' mean power shared by the global paths.
// Dividing by it makes one fresh photon one unit of brightness.
float meanPhotonPower(const Scene& scene, const FrameParams& params) {
    double power = 0.0;
    for (const Light& light : scene.lights) {
        power += (double(light.power.x) + double(light.power.y) + double(light.power.z)) / 3.0;
    }
    double photon = power / double(std::max(params.globalPaths, 1u));
    return photon > 0.0 ? float(photon) : 1.0f;
}

}  // namespace

void Viewer::drawFrame() {
    // The frame's parameters; prepare() may reallocate buffers, so the descriptor sets that point
    // at them are written after it (no submitted frame uses them now).
    const FrameParams& params = renderer_->beginFrame();
    TargetImage target;
    if (swapchain_) {
        if (!swapchain_->acquire(frame_.acquired, target)) {
            recreateSwapchain();
            imgui_->render(VK_NULL_HANDLE, false);
            return;
        }
    } else {
        target = offscreen_->target();
    }
    bool dots = state_.view == DisplayView::Dots;
    if (dots) {
        dots_->resize(params.width, params.height);
    }
    bool aov = isAovView(state_.view) && keepsAovs(renderer_->settings());
    VkBuffer image = aov                                   ? gpu_->buffer(BINDING_AOVS)
                     : denoises(renderer_->settings()) ? gpu_->buffer(BINDING_DENOISED)
                                                      : gpu_->accumulationBuffer();
    display_->setSources(image, dots_->buffer());

    bool scripted = options_.frames > 0;
    if (scripted && !options_.screenshot.empty() && framesDrawn_ + 1 == options_.frames) {
        frame_.screenshot = options_.screenshot;
    } else if (state_.screenshot) {
        frame_.screenshot = nextScreenshotPath(screenshotCount_);
    }
    state_.screenshot = false;
    bool copy = !frame_.screenshot.empty() && (!swapchain_ || swapchain_->canCopyFrom());
    if (!frame_.screenshot.empty() && !copy) {
        report("this swapchain's images cannot be copied: no screenshot");
        frame_.screenshot.clear();
    }
    bool hud = state_.showHud && (!copy || state_.screenshotHud);

    VkCommandBuffer cmd = frame_.cmd;
    VK_CHECK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    passTimer_->reset(cmd);

    gpu_->recordInto(cmd);
    renderer_->recordFrame();
    gpu_->recordStatsReadback(cmd);
    passTimer_->mark(cmd, 0);
    if (dots) {
        float depthTolerance = state_.dotsOcclusion ? 0.03f : 0.0f;
        dots_->record(cmd, *gpu_, state_.dotsBrightness / meanPhotonPower(renderer_->scene(), params), depthTolerance);
    }
    passTimer_->mark(cmd, 1);
    // The accumulation is complete before the display pass's fragment shader reads it.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);

    DisplayPush push{};
    push.width = params.width;
    push.height = params.height;
    push.targetWidth = target.extent.width;
    push.targetHeight = target.extent.height;
    push.source = dots ? DISPLAY_DOTS : DISPLAY_IMAGE;
    if (aov) {
        push.source = state_.view == DisplayView::Albedo   ? DISPLAY_ALBEDO
                      : state_.view == DisplayView::Normal ? DISPLAY_NORMAL
                                                           : DISPLAY_DEPTH;
    }
    push.curve = std::uint32_t(state_.tonemap);
    push.scale = std::exp2(state_.exposure);
    display_->begin(cmd, target);
    display_->draw(cmd, push);
    passTimer_->mark(cmd, 2);
    imgui_->render(cmd, hud);
    display_->end(cmd);
    passTimer_->mark(cmd, 3);
    if (copy) {
        screenshot_->record(cmd, target, swapchain_ ? swapchain_->format().format : kOffscreenFormat,
                            display_->finalLayout());
    }
    // This frame's reads (display and dots of the accumulation, the photon maps, the hit points,
    // the indirect group counts) are done before the next frame's stages overwrite them.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                               VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                      0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0);
    VK_CHECK(vkEndCommandBuffer(cmd));

    // The compute stages start at once; only the render pass waits for the swapchain image.
    VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSemaphore renderFinished = swapchain_ ? swapchain_->renderFinished(target.index) : VK_NULL_HANDLE;
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = swapchain_ ? 1 : 0;
    submit.pWaitSemaphores = &frame_.acquired;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    submit.signalSemaphoreCount = swapchain_ ? 1 : 0;
    submit.pSignalSemaphores = &renderFinished;
    VK_CHECK(vkQueueSubmit(context_->queue, 1, &submit, frame_.done));
    frame_.pending = true;
    framesDrawn_ += 1;
    if (swapchain_ && !swapchain_->present(target)) {
        swapchainStale_ = true;
    }
}

void Viewer::finishFrame() {
    if (!frame_.pending) {
        return;
    }
    VK_CHECK(vkWaitForFences(context_->device, 1, &frame_.done, VK_TRUE, UINT64_MAX));
    VK_CHECK(vkResetFences(context_->device, 1, &frame_.done));
    frame_.pending = false;

    renderer_->endFrame(gpu_->frameResult());
    const FrameStats& stats = renderer_->lastFrameStats();
    FrameRecord record;
    auto now = std::chrono::steady_clock::now();
    record.loopMs = std::chrono::duration<double, std::milli>(now - lastFinish_).count();
    lastFinish_ = now;
    record.stages = stats.ms;
    record.passes = passTimer_->read();
    double paths = double(stats.emittedPaths());
    double photonMs = stats.ms[STAGE_TRACE_PHOTONS];
    record.photonsPerSecond = photonMs > 0.0 ? paths / (photonMs * 1e-3) : 0.0;
    log_.add(record);

    if (!frame_.screenshot.empty()) {
        screenshot_->save(frame_.screenshot);
        report("saved " + frame_.screenshot);
        frame_.screenshot.clear();
    }
    context_->checkValidation("a viewer frame");
}

void Viewer::recreateSwapchain() {
    finishFrame();
    VkExtent2D size = window_->framebufferSize();
    if (size.width == 0 || size.height == 0) {
        swapchainStale_ = true;  // minimized: again when it comes back
        return;
    }
    swapchain_->create(size, display_->renderPass(), state_.vsync);
    swapchainStale_ = false;
}

}  // namespace photon::viewer
