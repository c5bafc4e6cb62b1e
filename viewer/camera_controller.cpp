#include "camera_controller.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace photon::viewer {
namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kPoleMargin = kPi / 180.0f;  // pitch stops 1° short of the poles

glm::vec3 rotate(glm::vec3 v, float angle, glm::vec3 axis) {
    return glm::vec3(glm::rotate(glm::mat4(1.0f), angle, axis) * glm::vec4(v, 0.0f));
}

}  // namespace

CameraController::CameraController(const CameraDesc& camera, float sceneSize) : sceneSize_(std::max(sceneSize, 1e-6f)) {
    setCamera(camera);
}

void CameraController::setCamera(const CameraDesc& camera) {
    camera_ = camera;
    worldUp_ = glm::normalize(camera.up);
    camera_.up = worldUp_;
}

glm::vec3 CameraController::forward() const { return glm::normalize(camera_.lookAt - camera_.position); }

glm::vec3 CameraController::right() const { return glm::normalize(glm::cross(forward(), worldUp_)); }

float CameraController::distance() const { return glm::length(camera_.lookAt - camera_.position); }

glm::vec3 CameraController::turn(glm::vec3 offset, float yaw, float pitch) const {
    glm::vec3 axis = glm::normalize(glm::cross(offset, worldUp_));
    float elevation = std::asin(std::clamp(glm::dot(glm::normalize(offset), worldUp_), -1.0f, 1.0f));
    float limit = 0.5f * kPi - kPoleMargin;
    float target = std::clamp(elevation + pitch, -limit, limit);
    glm::vec3 pitched = rotate(offset, target - elevation, axis);
    return rotate(pitched, yaw, worldUp_);
}

void CameraController::orbit(glm::vec2 pixels, float viewHeight) {
    glm::vec2 angle = pixels * (kPi / std::max(viewHeight, 1.0f));
    // Dragging right swings the camera left around the target, so the scene turns with the mouse.
    glm::vec3 offset = camera_.position - camera_.lookAt;
    camera_.position = camera_.lookAt + turn(offset, -angle.x, angle.y);
}

void CameraController::look(glm::vec2 pixels, float viewHeight) {
    glm::vec2 angle = pixels * (0.5f * kPi / std::max(viewHeight, 1.0f));
    glm::vec3 offset = camera_.lookAt - camera_.position;
    camera_.lookAt = camera_.position + turn(offset, -angle.x, -angle.y);
}

void CameraController::pan(glm::vec2 pixels, float viewHeight) {
    // One window height of motion moves by the height the field of view spans at lookAt.
    float tanHalf = std::tan(0.5f * camera_.fovY * kPi / 180.0f);
    float unitsPerPixel = 2.0f * distance() * tanHalf / std::max(viewHeight, 1.0f);
    glm::vec3 r = right();
    glm::vec3 u = glm::cross(r, forward());
    glm::vec3 move = (-pixels.x * r + pixels.y * u) * unitsPerPixel;
    camera_.position += move;
    camera_.lookAt += move;
}

void CameraController::zoom(float steps) {
    float d = distance() * std::pow(0.9f, steps);
    d = std::max(d, 1e-3f * sceneSize_);
    camera_.position = camera_.lookAt - forward() * d;
}

void CameraController::fly(const FlyInput& input, float seconds, float speed) {
    glm::vec3 move = input.forward * forward() + input.right * right() + input.up * worldUp_;
    if (glm::dot(move, move) == 0.0f) {
        return;
    }
    move *= speed * sceneSize_ * seconds;
    camera_.position += move;
    camera_.lookAt += move;
}

}  // namespace photon::viewer
