// Mouse and keys: the camera (orbit, look, pan, zoom, fly), the selected light, and the
// shortcuts. Input meant for the HUD (the pointer over it, typing in a field) is left to it.
#include "viewer.h"

#include <GLFW/glfw3.h>

namespace photon::viewer {

void Viewer::handleInput(float seconds) {
    if (!window_) {
        return;
    }
    glm::dvec2 cursor(window_->cursorX(), window_->cursorY());
    glm::vec2 delta(cursor - cursor_);
    cursor_ = cursor;
    float height = float(targetExtent().height);
    bool left = window_->buttonDown(GLFW_MOUSE_BUTTON_LEFT);
    bool right = window_->buttonDown(GLFW_MOUSE_BUTTON_RIGHT);
    bool middle = window_->buttonDown(GLFW_MOUSE_BUTTON_MIDDLE);
    bool shift = window_->keyDown(GLFW_KEY_LEFT_SHIFT) || window_->keyDown(GLFW_KEY_RIGHT_SHIFT);

    // A drag belongs to the camera if it began outside the HUD, wherever the pointer goes then.
    bool anyButton = left || right || middle;
    dragging_ = anyButton && (dragging_ || !imgui_->wantsMouse());
    if (dragging_) {
        if (middle || (left && shift)) {
            camera_.pan(delta, height);
        } else if (left) {
            camera_.orbit(delta, height);
        } else if (right) {
            camera_.look(delta, height);
        }
    }
    float scroll = window_->takeScroll();
    if (!imgui_->wantsMouse() && scroll != 0.0f) {
        camera_.zoom(scroll);
    }
    for (const std::string& path : window_->takeDroppedPaths()) {
        state_.openScene = path;
    }

    std::vector<KeyPress> presses = window_->takeKeyPresses();
    if (imgui_->typing()) {
        return;
    }
    for (const KeyPress& press : presses) {
        handleKey(press.key);
    }
    auto axis = [&](int negative, int positive) {
        return (window_->keyDown(positive) ? 1.0f : 0.0f) - (window_->keyDown(negative) ? 1.0f : 0.0f);
    };
    float speed = state_.flySpeed * (shift ? 4.0f : 1.0f);
    FlyInput fly{axis(GLFW_KEY_S, GLFW_KEY_W), axis(GLFW_KEY_A, GLFW_KEY_D), axis(GLFW_KEY_Q, GLFW_KEY_E)};
    camera_.fly(fly, seconds, speed);

    // The selected light moves in the camera's horizontal plane with the arrows, up and down with
    // Page Up and Page Down.
    glm::vec3 nudge(axis(GLFW_KEY_LEFT, GLFW_KEY_RIGHT), axis(GLFW_KEY_PAGE_DOWN, GLFW_KEY_PAGE_UP),
                    axis(GLFW_KEY_DOWN, GLFW_KEY_UP));
    if (lights_.lightCount() > 0 && nudge != glm::vec3(0.0f)) {
        const CameraDesc& c = camera_.camera();
        glm::vec3 up = glm::normalize(c.up);
        glm::vec3 forward = c.lookAt - c.position;
        forward = glm::normalize(forward - glm::dot(forward, up) * up);
        glm::vec3 side = glm::cross(forward, up);
        float step = speed * lights_.loaded().diagonal() * seconds;
        lights_.move(state_.selectedLight, step * (nudge.x * side + nudge.y * up + nudge.z * forward));
        state_.lightsChanged = true;
    }
}

void Viewer::handleKey(int key) {
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) {
        state_.view = DisplayView(key - GLFW_KEY_1);
        return;
    }
    if (key == GLFW_KEY_0) {  // the tenth view
        state_.view = DisplayView::Volume;
        return;
    }
    switch (key) {
        case GLFW_KEY_ESCAPE: window_->requestClose(); break;
        case GLFW_KEY_H:
        case GLFW_KEY_F1: state_.showHud = !state_.showHud; break;
        case GLFW_KEY_P:
        case GLFW_KEY_F12: state_.screenshot = true; break;
        case GLFW_KEY_V:
            state_.vsync = !state_.vsync;
            state_.vsyncChanged = true;
            break;
        case GLFW_KEY_R: state_.resetCamera = true; break;
        case GLFW_KEY_F5: state_.reloadScene = true; break;
        case GLFW_KEY_EQUAL:
        case GLFW_KEY_KP_ADD: state_.exposure += 0.5f; break;
        case GLFW_KEY_MINUS:
        case GLFW_KEY_KP_SUBTRACT: state_.exposure -= 0.5f; break;
        default: break;
    }
}

}  // namespace photon::viewer
