// How photon-view was started (apps/photon_view.cpp parses these from the command line).
#pragma once

#include <cstdint>
#include <string>

#include "core/loaders/model_loader.h"
#include "core/scene/camera_path.h"
#include "core/scene/scene.h"
#include "core/settings/settings.h"

namespace photon::viewer {

// What the image shows: the backend's views, and the viewer's own photon dots.
// Albedo, Normal, Depth: the auxiliary images (shared/aov.h) the denoiser is guided by.
enum class DisplayView : std::uint32_t { Final, Direct, Global, Caustic, Dots, Grid, Albedo, Normal, Depth, Volume };
constexpr std::uint32_t kDisplayViewCount = 10;
inline bool isAovView(DisplayView v) { return v == DisplayView::Albedo || v == DisplayView::Normal || v == DisplayView::Depth; }
const char* toString(DisplayView view);

}  // namespace photon::viewer

namespace photon {
template <>
constexpr std::uint32_t enumCount<viewer::DisplayView>() { return viewer::kDisplayViewCount; }
}  // namespace photon

namespace photon::viewer {

// A scripted run's frames are this far apart on a camera path, whatever they cost (repeatable).
constexpr double kScriptedFrameSeconds = 1.0 / 60.0;

struct ViewerOptions {
    std::string scenePath;           // empty: the built-in Cornell box
    Scene scene;                     // loaded from scenePath (or the built-in one)
    RenderSettings settings;         // the scene's, with the command line's overrides
    DisplayView view = DisplayView::Final;
    std::string device;              // Vulkan device: index or part of the name
    bool validation = false;         // validation layer on; any message is an error
    bool vsync = true;
    bool offscreen = false;          // no window: draw into an image (machines without a display)
    bool hud = true;                 // draw the HUD
    std::uint32_t frames = 0;        // scripted: render this many frames, then exit (0: until closed)
    std::string screenshot;          // scripted: save the last frame here (PNG)
    bool screenshotHud = false;      // screenshots include the HUD
    std::uint32_t resizeAfter = 0;   // scripted: resize the window after this many frames (0: never)
    std::uint32_t resizeWidth = 0;
    std::uint32_t resizeHeight = 0;
    std::string statsPath;           // write frame-time medians as JSON here at exit
    bool followPath = false;         // the camera follows cameraPath from the scene's camera:
    CameraPath cameraPath;           // by the clock, or kScriptedFrameSeconds a frame with --frames
    PathPolicy paths;                // where the files a model names may lie (reloads too)
};

}  // namespace photon::viewer
