// Applying what the person changed (ViewState, camera, lights) to the backend between frames,
// and opening, reloading and watching scene files.
#include "viewer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "core/error.h"
#include "core/scene_loader.h"

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
    }
    return View::Final;
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
        backend_->setScene(lights_.scene());
        sceneSet = true;
    }
    applySettings();
    if (sceneSet || !sameCamera(camera_.camera(), backend_->camera())) {
        backend_->setCamera(camera_.camera());
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
        s.exposure = state_.exposure;  // display only: kept in step, never a reason to restart
        s.tonemap = state_.tonemap;
        const RenderSettings& current = backend_->settings();
        if (!changed && s.width == current.width && s.height == current.height && s.view == current.view) {
            return;
        }
        try {
            backend_->setSettings(s);
            backend_->prepare();
            goodSettings_ = s;
            return;
        } catch (const InputError& e) {
            if (!started_ || options_.frames > 0 || attempt == 3) {
                throw;  // at start, and in scripted runs, a bad request fails the program
            }
            state_.message = e.what();
            std::fprintf(stderr, "photon-view: %s\n", e.what());
            if (s.width != goodSettings_.width || s.height != goodSettings_.height) {
                state_.renderScale *= 0.5f;
            } else {
                state_.settings = goodSettings_;
            }
            changed = true;
        }
    }
}

// Opens a scene file (the built-in Cornell box for an empty path when reloading). An unreadable
// or invalid file leaves the current scene and says why in the HUD.
void Viewer::loadScene(const std::string& path, bool keepCameraAndSettings) {
    Scene scene;
    try {
        scene = path.empty() ? defaultScene() : loadSceneFile(path);
        sceneTime_ = path.empty() ? std::filesystem::file_time_type{} : std::filesystem::last_write_time(path);
    } catch (const std::exception& e) {
        state_.message = e.what();
        std::fprintf(stderr, "photon-view: %s\n", e.what());
        return;
    }
    scenePath_ = path;
    lights_ = LightEditor(scene);
    state_.selectedLight = 0;
    state_.animateLight = false;
    if (!keepCameraAndSettings) {
        camera_ = CameraController(scene.camera, scene.diagonal());
        state_.settings = scene.render;
        state_.exposure = scene.render.exposure;
        state_.tonemap = scene.render.tonemap;
    }
    backend_->setScene(lights_.scene());
    state_.settingsChanged = true;
    state_.message = "loaded " + (path.empty() ? scene.name : path);
    std::fprintf(stderr, "photon-view: %s\n", state_.message.c_str());
    setTitle();
}

// Reloads the scene file when it changes on disk (checked twice a second), so that editing its
// lights or objects shows at once.
void Viewer::watchSceneFile() {
    auto now = std::chrono::steady_clock::now();
    if (!state_.watchScene || scenePath_.empty() || now - lastWatch_ < std::chrono::milliseconds(500)) {
        return;
    }
    lastWatch_ = now;
    std::error_code error;
    auto time = std::filesystem::last_write_time(scenePath_, error);
    if (!error && time != sceneTime_) {
        loadScene(scenePath_, true);
    }
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
