// photon-view: the windowed viewer. Opens a scene (or the built-in Cornell box) and renders it
// progressively with the Vulkan backend while you move through it; see docs/viewer.md.
//
//   photon-view [scene.json] [render options of photon-render] --vsync on|off --validation
//   photon-view ... --frames N --screenshot out.png [--resize-after K WxH]   (scripted: exits 0)
//   photon-view ... --offscreen --frames N [--stats times.json]              (no display needed)
//
// Exit codes: 0 success, 2 bad input (scene, options), 1 runtime failure (no window, no device,
// a Vulkan validation message).
#include <cstdio>
#include <cstdlib>
#include <string>
#include <tuple>
#include <vector>

#include <CLI/CLI.hpp>

#include "apps/render_options.h"
#include "core/image/image.h"
#include "core/loaders/scene_loader.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"
#include "core/system/output_file.h"
#include "core/system/program.h"
#include "viewer/viewer.h"

namespace photon {
namespace {

int run(int argc, char** argv) {
    CLI::App app{"Photon: interactive progressive photon mapping with Vulkan", "photon-view"};
    viewer::ViewerOptions o;
    RenderOptions render;
    std::string vsync = "on";
    std::vector<std::string> resize;
    bool hud = true;
    app.add_option("scene", o.scenePath, "Scene file (JSON); the built-in Cornell box if omitted")->check(kFileName);
    std::string backendName = "vulkan";
    app.add_option("--backend", backendName, "vulkan (auto means it too): the viewer renders with Vulkan");
    app.add_option("--device", o.device, "GPU to use: index or part of its name");
    addSwitch(app, "--validation", o.validation, "Vulkan validation layer on; any message fails");
    app.add_option("--vsync", vsync, "Wait for the display's refresh: on|off")->check(CLI::IsMember({"on", "off"}));
    addSwitch(app, "--offscreen", o.offscreen, "No window: draw into an image (needs --frames)");
    addSwitch(app, "--hud", hud, "Start with the HUD (on; --no-hud starts without it, H or F1 shows it)");
    app.add_option("--screenshot", o.screenshot, "With --frames: save the last frame here (PNG)")->check(kFileName);
    addSwitch(app, "--screenshot-hud", o.screenshotHud, "Screenshots include the HUD");
    app.add_option("--resize-after", resize, "With --frames: after K frames resize the window to WxH")
        ->expected(2)
        ->option_text("K WxH");
    app.add_option("--stats", o.statsPath, "Write the median frame times as JSON at exit")->check(kFileName);
    std::string cameraPath;
    app.add_option("--camera-path", cameraPath,
                   "Move the camera along a path: orbit:SECONDS turns it about what it looks at once every SECONDS "
                   "(with --frames, 1/60 s a frame)");
    addRenderOptions(app, render);
    // --frames makes a run scripted; --view also takes the viewer's own "dots".
    app.get_option("--frames")->description("Render this many frames, then exit (scripted use)");
    const std::string viewNames = findSetting("view")->choices + "|dots|albedo|normal|depth";
    app.get_option("--view")->description("What to show: " + viewNames);
    if (int code = parseCommandLine(app, argc, argv); code >= 0) {
        return code;
    }

    if (backendName != "vulkan" && backendName != "auto") {
        throw InputError("--backend: " + quote(backendName) +
                         ": photon-view renders with Vulkan, whose images its window shows (photon-render has cpu and cuda)");
    }
    std::string& viewName = render.values["--view"];
    // The viewer's own views: the photon dots and the auxiliary images.
    bool ownView = false;
    for (viewer::DisplayView v : {viewer::DisplayView::Dots, viewer::DisplayView::Albedo, viewer::DisplayView::Normal,
                                  viewer::DisplayView::Depth}) {
        if (viewName == viewer::toString(v)) {
            o.view = v;
            ownView = true;
        }
    }
    if (ownView) {
        // What the renderer runs under them: the dots need no estimates (direct light only).
        viewName = o.view == viewer::DisplayView::Dots ? "direct" : "final";
    } else if (View v; !viewName.empty() && !parse(viewName, v)) {
        throw InputError("--view: unknown value '" + viewName + "' (expected " + viewNames + ")");
    }
    o.paths = render.paths;
    o.scene = app.count("scene") == 0 ? defaultScene() : loadSceneFile(o.scenePath, o.paths);
    applyEnvironmentOption(app, render, o.scene);
    o.settings = o.scene.render;
    applyRenderOptions(app, render, o.settings);
    chooseDefaults(o.settings, true);  // the viewer accumulates while the view stays
    chooseInteractive(o.settings);     // ... and carries it along when the view moves
    validateSettings(o.settings);
    if (!ownView) {
        const viewer::DisplayView views[] = {viewer::DisplayView::Final, viewer::DisplayView::Direct,
                                             viewer::DisplayView::Global, viewer::DisplayView::Caustic,
                                             viewer::DisplayView::Grid, viewer::DisplayView::Volume};
        o.view = views[std::uint32_t(o.settings.view)];
    }
    if (!cameraPath.empty()) {
        o.cameraPath = parseCameraPath(cameraPath, "--camera-path");
        o.followPath = true;
    }
    o.vsync = vsync == "on";
    o.hud = hud;
    o.frames = app.count("--frames") > 0 ? o.settings.frames : 0;
    if (!resize.empty()) {
        char* end = nullptr;
        unsigned long frames = std::strtoul(resize[0].c_str(), &end, 10);
        if (resize[0].empty() || *end != '\0' || frames == 0 || frames > 1000000) {
            throw InputError("--resize-after: '" + resize[0] + "' is not a number of frames");
        }
        o.resizeAfter = std::uint32_t(frames);
        std::tie(o.resizeWidth, o.resizeHeight) = parseImageSize(resize[1], "--resize-after");
    }
    if (o.frames == 0 && (o.offscreen || !o.screenshot.empty() || o.resizeAfter > 0)) {
        throw InputError("--offscreen, --screenshot and --resize-after need --frames N");
    }
    if (!o.screenshot.empty() && imageFormatFor(o.screenshot) != ImageFormat::Png) {
        throw InputError("--screenshot: " + o.screenshot + ": screenshots are PNG files");
    }
    if (!o.screenshot.empty()) {
        checkOutputPath(o.screenshot, "screenshot");
    }
    if (!o.statsPath.empty()) {
        checkOutputPath(o.statsPath, "stats");
    }

    viewer::Viewer view(o);
    view.run();
    return 0;
}

}  // namespace
}  // namespace photon

int main(int argc, char** argv) {
    return photon::runProgram("photon-view", [&] { return photon::run(argc, argv); });
}
