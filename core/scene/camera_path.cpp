#include "core/scene/camera_path.h"

#include <cmath>
#include <cstdlib>

#include "core/system/error.h"

namespace photon {
namespace {

// A plain decimal number: no "nan", "inf" or hexadecimal, nothing after it.
bool parseSeconds(const std::string& text, double& value) {
    if (text.empty() || text.find_first_not_of("0123456789+-.eE") != std::string::npos) {
        return false;
    }
    char* end = nullptr;
    value = std::strtod(text.c_str(), &end);
    return *end == '\0';
}

}  // namespace

CameraPath parseCameraPath(const std::string& text, const std::string& option) {
    const std::string kind = "orbit:";
    double seconds = 0.0;
    if (text.compare(0, kind.size(), kind) != 0 || !parseSeconds(text.substr(kind.size()), seconds) ||
        !(seconds >= 0.1 && seconds <= 1.0e6)) {
        throw InputError(option + ": '" + printable(text) + "' is not orbit:SECONDS (one turn in 0.1 to 1e6 seconds)");
    }
    CameraPath path;
    path.seconds = seconds;
    return path;
}

CameraDesc cameraAt(const CameraPath& path, const CameraDesc& start, double t) {
    // Rodrigues' rotation of the camera's offset from its target about the unit up vector.
    double turns = t / path.seconds;
    double angle = 2.0 * 3.14159265358979323846 * (turns - std::floor(turns));
    glm::dvec3 k = glm::normalize(glm::dvec3(start.up));
    glm::dvec3 v = glm::dvec3(start.position) - glm::dvec3(start.lookAt);
    glm::dvec3 turned = v * std::cos(angle) + glm::cross(k, v) * std::sin(angle) + k * glm::dot(k, v) * (1.0 - std::cos(angle));
    CameraDesc camera = start;
    camera.position = glm::vec3(glm::dvec3(start.lookAt) + turned);
    return camera;
}

}  // namespace photon
