// The HUD: what the frame costs (fps, each stage's GPU time, photons per second, frames
// accumulated, the device) and the panel that edits the ViewState. Dear ImGui widgets only;
// imgui_layer.cpp sets ImGui up and draws them.
#pragma once

#include <cstdint>
#include <string>

#include "core/frame/backend.h"
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
    float radius[2] = {};           // the query radii in use (global, caustic)
    bool windowed = true;
};

// Builds this frame's HUD widgets, editing `state` and moving `lights`.
void buildHud(ViewState& state, LightEditor& lights, const HudInfo& info);

}  // namespace photon::viewer
