// Frame times: the GPU time of the backend's stages (its timestamps) and of the viewer's passes
// (ours), and the wall-clock time of each trip round the frame loop. Kept for the HUD (fps over
// the last half second) and for the medians printed at exit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/frame/renderer.h"
#include "vulkan/context.h"

namespace photon::viewer {

// Milliseconds of the viewer's own GPU work in a frame.
struct PassTimes {
    double dots = 0.0;     // photon dots (0 unless shown)
    double display = 0.0;  // the full-screen tone-mapping triangle
    double hud = 0.0;      // Dear ImGui's draw calls
    double total() const { return dots + display + hud; }
};

// Timestamps around the viewer's passes: after the backend's frame, after the dots, after the
// display triangle, after the HUD. One frame at a time.
class PassTimer {
public:
    explicit PassTimer(const vk::Context& context);
    ~PassTimer();
    PassTimer(const PassTimer&) = delete;
    PassTimer& operator=(const PassTimer&) = delete;

    void reset(VkCommandBuffer cmd);  // outside a render pass, before the first mark
    void mark(VkCommandBuffer cmd, std::uint32_t index);  // index 0..3, in order
    PassTimes read();  // once the frame's commands have completed

private:
    const vk::Context& context_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
};

struct FrameRecord {
    double loopMs = 0.0;             // wall-clock time since the previous frame started
    StageTimes stages;               // the backend's stages
    PassTimes passes;                // ours
    double photonsPerSecond = 0.0;   // emitted paths / time of the photon pass
};

class FrameLog {
public:
    void add(const FrameRecord& record);
    const FrameRecord& last() const { return records_.back(); }
    bool empty() const { return records_.empty(); }
    std::size_t size() const { return records_.size(); }
    // Frames per second over the last half second of frames.
    double fps() const;
    // The median of every column over the frames after the first `skip` (pipeline warm-up).
    FrameRecord median(std::size_t skip) const;

private:
    std::vector<FrameRecord> records_;
};

}  // namespace photon::viewer
