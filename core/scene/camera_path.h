// Scripted camera motion: where a camera is a given time along a path. The viewer's
// --camera-path moves its camera along one (a fixed step a frame in scripted runs, so that a run
// is repeatable), and photon-converge --camera-path measures the images of a moving view.
#pragma once

#include <string>

#include "core/scene/scene.h"

namespace photon {

struct CameraPath {
    // An orbit: the camera turns about the line through the point it looks at along its up
    // vector, once every `seconds`, keeping its height and distance.
    double seconds = 0.0;
};

// "orbit:SECONDS". Throws InputError naming `option` for anything else.
CameraPath parseCameraPath(const std::string& text, const std::string& option);

// `start` carried `t` seconds along the path.
CameraDesc cameraAt(const CameraPath& path, const CameraDesc& start, double t);

}  // namespace photon
