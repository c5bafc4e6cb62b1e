// The HUD: what the frame costs (fps, each stage's GPU time, photons per second, frames
// accumulated, the device) and the panel that edits the ViewState. Dear ImGui widgets only;
// imgui_layer.cpp sets ImGui up and draws them.
#pragma once

#include <cstdint>
#include <string>

#include "core/frame/renderer.h"
#include "frame_log.h"
#include "light_editor.h"
#include "state.h"

namespace photon::viewer {

struct HudInfo {
    std::string device;             // the GPU's name
    std::string scene;              // the scene's name, or its file
    std::uint32_t windowWidth = 0;  // the target's size
    std::uint32_t windowHeight = 0;
    const char* presentMode = "";   // "fifo (vsync)", "mailbox", ... or "offscreen"
    double fps = 0.0;               // over the last half second
    FrameRecord frame;              // the last completed frame's times
    FrameStats stats;               // its photon counts
    std::uint32_t accumulated = 0;  // frames in the image
    float radius[MAP_COUNT] = {};   // the query radii in use, by map
    bool windowed = true;
};

// Where the panel starts in a window of this size: 340 px wide where there is room, never more
// than 36% of the window (at least 240 px), never taller than the window (it scrolls), and the
// Render section and the stage times open only in a window tall enough to show them whole (at
// 640×480 the open panel covered 55% of the image and was cut off at the bottom; with the stage
// times open, 84% of its height).
struct HudLayout {
    float width = 340.0f;
    float maxHeight = 0.0f;
    bool renderOpen = true;
};
HudLayout hudLayout(float windowWidth, float windowHeight);

// Builds this frame's HUD widgets, editing `state` and moving `lights`.
void buildHud(ViewState& state, LightEditor& lights, const HudInfo& info);

}  // namespace photon::viewer
