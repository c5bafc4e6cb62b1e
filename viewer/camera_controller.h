// A free camera over CameraDesc: orbit, pan and zoom about the point looked at, look around from
// where the camera stands, and fly. Plain math on the description (no window system), so that
// tests can drive it; viewer_input.cpp feeds it mouse and keys.
#pragma once

#include <glm/glm.hpp>

#include "core/scene/scene.h"

namespace photon::viewer {

struct FlyInput {
    float forward = 0.0f;  // -1..1: S / W
    float right = 0.0f;    // -1..1: A / D
    float up = 0.0f;       // -1..1: Q / E, along the world's up
};

class CameraController {
public:
    // `sceneSize` (the scene's diagonal) sets the flying speed and the closest zoom.
    explicit CameraController(const CameraDesc& camera = {}, float sceneSize = 1.0f);

    const CameraDesc& camera() const { return camera_; }
    void setCamera(const CameraDesc& camera);

    // Mouse motions are in pixels of a window `viewHeight` pixels tall: dragging across the
    // window's height turns the view by about 180° or pans by the field of view.
    void orbit(glm::vec2 pixels, float viewHeight);  // about lookAt, keeping the distance
    void look(glm::vec2 pixels, float viewHeight);   // about the camera's position
    void pan(glm::vec2 pixels, float viewHeight);    // position and lookAt along the image plane
    void zoom(float steps);                          // towards lookAt: each step 10% closer
    // Moves position and lookAt together, `speed` scene diagonals per second for `seconds`.
    void fly(const FlyInput& input, float seconds, float speed);

    float distance() const;  // from the camera to lookAt

private:
    glm::vec3 forward() const;
    glm::vec3 right() const;
    // `offset` turned by `yaw` about the world's up and by `pitch` about `axis`, with the pitch
    // limited so that the result stays at least 1° away from straight up or down.
    glm::vec3 turn(glm::vec3 offset, float yaw, float pitch) const;

    CameraDesc camera_;
    glm::vec3 worldUp_{0.0f, 1.0f, 0.0f};
    float sceneSize_ = 1.0f;
};

}  // namespace photon::viewer
