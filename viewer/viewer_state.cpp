// Applying what the person changed (ViewState, camera, lights) to the backend between frames,
// and opening, reloading and watching scene files.
#include "viewer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "core/frame/scene_settings.h"
#include "core/loaders/scene_loader.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"

namespace photon::viewer {
namespace {

bool sameCamera(const CameraDesc& a, const CameraDesc& b) {
    return a.position == b.position && a.lookAt == b.lookAt && a.up == b.up && a.fovY == b.fovY &&
           a.lensRadius == b.lensRadius && a.focusDistance == b.focusDistance;
}

// The backend's view for a display view: the photon dots need the hit points and the photon
// maps but no estimates, so the backend renders direct light only under them.
View backendView(DisplayView view) {
    switch (view) {
        case DisplayView::Final: return View::Final;
        case DisplayView::Direct: return View::Direct;
        case DisplayView::Global: return View::Global;
        case DisplayView::Caustic: return View::Caustic;
        case DisplayView::Dots: return View::Direct;
        case DisplayView::Grid: return View::Grid;
        case DisplayView::Albedo:
        case DisplayView::Normal:
        case DisplayView::Depth: return View::Final;
        case DisplayView::Volume: return View::Volume;
    }
    throw std::logic_error("unknown display view");
}

}  // namespace

void Viewer::applyChanges() {
    if (swapchainStale_ || state_.vsyncChanged) {
        state_.vsyncChanged = false;
        recreateSwapchain();
    }
    if (!state_.openScene.empty()) {
        loadScene(std::exchange(state_.openScene, {}), false);
    }
    if (state_.reloadScene) {
        state_.reloadScene = false;
        loadScene(scenePath_, true);
    }
    finishLoadingScene();
    watchSceneFile();
    if (state_.resetCamera) {
        state_.resetCamera = false;
        camera_.setCamera(lights_.loaded().camera);
    }
    // A moved light: the scene is uploaded again (same sizes, so nothing is reallocated), which
    // also resets the backend's camera to the scene's: ours is set again below.
    bool sceneSet = false;
    if (state_.lightsChanged) {
        state_.lightsChanged = false;
        renderer_->setScene(lights_.scene());
        sceneSet = true;
    }
    applySettings();
    if (sceneSet) {
        renderer_->setCamera(camera_.camera());
    } else if (!sameCamera(camera_.camera(), renderer_->camera())) {
        renderer_->moveCamera(camera_.camera());  // the history follows it (--reproject)
    }
}

// The render settings, with the size the target asks for and the view the display needs. Only a
// real change reaches the backend (setSettings restarts the accumulation). A request the device
// cannot fit is refused with a message: too large an image renders at a smaller scale, other
// settings go back to the last ones the backend accepted.
void Viewer::applySettings() {
    bool changed = std::exchange(state_.settingsChanged, false);
    for (int attempt = 0;; ++attempt) {
        RenderSettings s = state_.settings;
        VkExtent2D extent = targetExtent();
        s.width = std::max(1u, std::uint32_t(std::lround(double(extent.width) * state_.renderScale)));
        s.height = std::max(1u, std::uint32_t(std::lround(double(extent.height) * state_.renderScale)));
        s.view = backendView(state_.view);
        s.aov = s.aov || isAovView(state_.view);  // the auxiliary images are kept to be shown
        s.exposure = state_.exposure;  // display only: kept in step, never a reason to restart
        s.tonemap = state_.tonemap;
        const RenderSettings& current = renderer_->settings();
        if (!changed && s.width == current.width && s.height == current.height && s.view == current.view &&
            s.aov == current.aov) {
            return;
        }
        try {
            renderer_->setSettings(s);
            renderer_->prepare();
            goodSettings_ = s;
            return;
        } catch (const InputError& e) {
            if (!started_ || options_.frames > 0 || attempt == 3) {
                throw;  // at start, and in scripted runs, a bad request fails the program
            }
            report(e.what());
            if (s.width != goodSettings_.width || s.height != goodSettings_.height) {
                state_.renderScale *= 0.5f;
            } else {
                state_.settings = goodSettings_;
            }
            changed = true;
        }
    }
}

// Opens a scene file (the built-in Cornell box for an empty path when reloading). The file is read
// and parsed on a thread of its own, with the reader of every program (regular files only, with a
// size cap), so that the frame loop never waits for it; installScene() takes the result. An
// unreadable or invalid file leaves the current scene and says why in the HUD.
void Viewer::loadScene(const std::string& path, bool keepCameraAndSettings) {
    if (path.empty()) {
        installScene(defaultScene(), path, keepCameraAndSettings);
        return;
    }
    if (loading_.valid()) {
        return;  // one load at a time; the watch notices later changes again
    }
    std::error_code error;
    sceneTime_ = std::filesystem::last_write_time(path, error);
    loadingPath_ = path;
    loadingKeeps_ = keepCameraAndSettings;
    loading_ = std::async(std::launch::async, [path, paths = options_.paths] { return loadSceneFile(path, paths); });
}

// Installs a scene whose loading has finished, if one has.
void Viewer::finishLoadingScene() {
    if (!loading_.valid() || loading_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
        return;
    }
    try {
        installScene(loading_.get(), loadingPath_, loadingKeeps_);
    } catch (const std::exception& e) {
        report(e.what());
    }
}

void Viewer::installScene(const Scene& scene, const std::string& path, bool keepCameraAndSettings) {
    scenePath_ = path;
    lights_ = LightEditor(scene);
    state_.selectedLight = 0;
    state_.animateLight = false;
    if (!keepCameraAndSettings) {
        camera_ = CameraController(scene.camera, scene.diagonal());
        state_.settings = scene.render;
        chooseDefaults(state_.settings, true);
        chooseInteractive(state_.settings);
        chooseSpectral(state_.settings, scene);
        choosePhotons(state_.settings, renderer_->runsOnCpu());
        state_.exposure = scene.render.exposure;
        state_.tonemap = scene.render.tonemap;
    }
    renderer_->setScene(lights_.scene());
    state_.settingsChanged = true;
    for (const std::string& warning : scene.warnings) {
        report(warning);
    }
    report("loaded " + (path.empty() ? scene.name : path));
    setTitle();
}

// A notice or an error: shown in the HUD, and printed once (not again while it stays the same).
void Viewer::report(const std::string& message) {
    if (message != state_.message) {
        std::fprintf(stderr, "photon-view: %s\n", printable(message).c_str());
    }
    state_.message = message;
}

// Reloads the scene file when it changes on disk (checked twice a second), so that editing its
// lights or objects shows at once.
void Viewer::watchSceneFile() {
    auto now = std::chrono::steady_clock::now();
    if (!state_.watchScene || scenePath_.empty() || loading_.valid() || now - lastWatch_ < std::chrono::milliseconds(500)) {
        return;
    }
    lastWatch_ = now;
    std::error_code error;
    auto time = std::filesystem::last_write_time(scenePath_, error);
    if (!error && time != sceneTime_) {
        loadScene(scenePath_, true);
    }
}

// --camera-path: the camera where the path is now, from the loaded scene's camera. The backend
// sees a moved camera (applyChanges), so the history follows it under --reproject.
void Viewer::followCameraPath(float seconds) {
    if (!options_.followPath) {
        return;
    }
    if (framesDrawn_ > 0) {
        pathSeconds_ += options_.frames > 0 ? kScriptedFrameSeconds : double(seconds);
    }
    camera_.setCamera(cameraAt(options_.cameraPath, lights_.loaded().camera, pathSeconds_));
}

// The circling light: the selected light goes round a circle of a tenth of the scene's diagonal
// about where it was when circling began, once every eight seconds.
void Viewer::animateLight(float seconds) {
    if (!state_.animateLight || lights_.lightCount() == 0) {
        lightCircleAngle_ = -1.0f;
        return;
    }
    std::uint32_t light = state_.selectedLight;
    float radius = 0.1f * lights_.loaded().diagonal();
    glm::vec3 up = glm::normalize(lights_.loaded().camera.up);
    glm::vec3 u = glm::normalize(glm::cross(up, std::abs(up.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1)));
    glm::vec3 v = glm::cross(up, u);
    if (lightCircleAngle_ < 0.0f) {
        lightCircleCentre_ = lights_.position(light) - radius * u;
        lightCircleAngle_ = 0.0f;
    }
    lightCircleAngle_ = std::fmod(lightCircleAngle_ + seconds * 6.2831853f / 8.0f, 6.2831853f);
    lights_.setPosition(light, lightCircleCentre_ + radius * (std::cos(lightCircleAngle_) * u + std::sin(lightCircleAngle_) * v));
    state_.lightsChanged = true;
}

}  // namespace photon::viewer
