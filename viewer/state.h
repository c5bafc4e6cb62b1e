// Everything a person can change while the viewer runs, edited by the HUD and the keys, and
// applied to the backend between frames (viewer_state.cpp). A change to the camera, a light or a
// render setting restarts the accumulation; display settings (view, exposure, tone curve) do not.
#pragma once

#include <cstdint>
#include <string>

#include "core/settings/settings.h"
#include "options.h"

namespace photon::viewer {

struct ViewState {
    RenderSettings settings;           // what the backend renders; width and height follow the window
    DisplayView view = DisplayView::Final;
    float exposure = 0.0f;             // stops, display only
    Tonemap tonemap = Tonemap::Aces;   // display only
    float renderScale = 1.0f;          // rendered pixels per window pixel (1, 1/2, 1/4)
    bool vsync = true;
    bool showHud = true;
    bool screenshotHud = false;        // screenshots include the HUD
    bool dotsOcclusion = true;         // photon dots behind the visible surface are hidden
    float dotsBrightness = 0.5f;       // brightness of a photon of the mean emitted power
    float flySpeed = 0.25f;            // scene diagonals per second
    std::uint32_t selectedLight = 0;
    std::uint32_t selectedMedium = 0;
    bool animateLight = false;         // the selected light circles about where it was
    bool watchScene = true;            // reload the scene file when it changes on disk

    // Requests, handled (and cleared) by the viewer between frames.
    bool settingsChanged = false;
    bool lightsChanged = false;
    bool vsyncChanged = false;
    bool resetCamera = false;
    bool reloadScene = false;
    bool screenshot = false;
    std::string openScene;             // a scene file to open instead of the current one

    std::string message;               // the last error or notice, shown in the HUD
};

}  // namespace photon::viewer
