// projectToPixel (shared/eye_trace.h) against cameraRay: a point on the ray through a pixel
// projects back into that pixel, for cameras turned every way and images of any aspect.
#include <gtest/gtest.h>

#include <cmath>

#include "core/scene/scene.h"
#include "shared/eye_trace.h"

namespace photon {
namespace {

struct CameraCase {
    glm::vec3 position;
    glm::vec3 lookAt;
    glm::vec3 up;
    float fovY;
    std::uint32_t width;
    std::uint32_t height;

    // The camera as the renderer makes it for this case's image.
    Camera camera() const {
        CameraDesc desc;
        desc.position = position;
        desc.lookAt = lookAt;
        desc.up = up;
        desc.fovY = fovY;
        return makeCamera(desc, width, height);
    }
};

const CameraCase kCameras[] = {
    {{0, 1, 3.9f}, {0, 1, 0}, {0, 1, 0}, 38.0f, 640, 480},          // the Cornell box's
    {{2, 3, -1}, {-0.5f, 0.2f, 0.7f}, {0, 1, 0}, 70.0f, 320, 400},  // looking down, portrait
    {{-5, 0.5f, 2}, {1, 0, -3}, {0.2f, 1, 0.1f}, 15.0f, 97, 31},    // tilted up vector, narrow
};

TEST(ProjectToPixel, InvertsCameraRayThroughPixelCentres) {
    for (const CameraCase& k : kCameras) {
        Camera camera = k.camera();
        for (std::uint32_t py = 0; py < k.height; py += 7) {
            for (std::uint32_t px = 0; px < k.width; px += 5) {
                Rng rng = rngCreate(py * k.width + px, 0u, 1u, STREAM_CAMERA);
                Ray ray = cameraRay(camera, px, py, k.width, k.height, FLAG_PIXEL_CENTER, rng);
                for (float t : {0.1f, 2.0f, 50.0f}) {
                    vec3 p = projectToPixel(camera, ray.origin + t * ray.direction, k.width, k.height);
                    ASSERT_NEAR(p.x, float(px) + 0.5f, 2e-3f) << "pixel " << px << "," << py << " t " << t;
                    ASSERT_NEAR(p.y, float(py) + 0.5f, 2e-3f) << "pixel " << px << "," << py << " t " << t;
                    ASSERT_NEAR(p.z, t * glm::dot(ray.direction, camera.forward), 1e-4f * t);
                }
            }
        }
    }
}

TEST(ProjectToPixel, JitteredRaysStayInsideTheirPixel) {
    const CameraCase& k = kCameras[1];
    Camera camera = k.camera();
    for (std::uint32_t i = 0; i < 2000; ++i) {
        std::uint32_t px = (i * 37u) % k.width;
        std::uint32_t py = (i * 101u) % k.height;
        Rng rng = rngCreate(i, 3u, 7u, STREAM_CAMERA);
        Ray ray = cameraRay(camera, px, py, k.width, k.height, 0u, rng);
        vec3 p = projectToPixel(camera, ray.origin + 3.0f * ray.direction, k.width, k.height);
        ASSERT_GE(p.x, float(px) - 1e-3f);
        ASSERT_LE(p.x, float(px + 1) + 1e-3f);
        ASSERT_GE(p.y, float(py) - 1e-3f);
        ASSERT_LE(p.y, float(py + 1) + 1e-3f);
    }
}

TEST(ProjectToPixel, CornersCentreAndBehind) {
    CameraDesc desc;
    desc.position = glm::vec3(0.0f);
    desc.lookAt = glm::vec3(0.0f, 0.0f, -1.0f);
    desc.fovY = 90.0f;  // tan(45°) = 1: the image spans ±aspect × ±1 at distance 1
    Camera camera = makeCamera(desc, 200, 100);
    vec3 centre = projectToPixel(camera, vec3(0.0f, 0.0f, -4.0f), 200, 100);
    EXPECT_NEAR(centre.x, 100.0f, 1e-4f);
    EXPECT_NEAR(centre.y, 50.0f, 1e-4f);
    EXPECT_NEAR(centre.z, 4.0f, 1e-6f);
    vec3 topLeft = projectToPixel(camera, vec3(-2.0f, 1.0f, -1.0f), 200, 100);
    EXPECT_NEAR(topLeft.x, 0.0f, 1e-4f);
    EXPECT_NEAR(topLeft.y, 0.0f, 1e-4f);
    vec3 bottomRight = projectToPixel(camera, vec3(4.0f, -2.0f, -2.0f), 200, 100);
    EXPECT_NEAR(bottomRight.x, 200.0f, 1e-3f);
    EXPECT_NEAR(bottomRight.y, 100.0f, 1e-3f);
    EXPECT_LT(projectToPixel(camera, vec3(0.3f, 0.2f, 1.0f), 200, 100).z, 0.0f);  // behind
}

}  // namespace
}  // namespace photon
