// Temporal reprojection (shared/reproject.h) on the CPU backend: a still camera renders as
// without it; when the camera moves, a pixel keeps its history exactly where its surface was seen
// directly and stays in view, and starts again where it came into view or is seen through a mirror
// or glass; the carried image is closer to the converged one than a restarted frame; lights and
// settings still restart. (Vulkan against the CPU: tests/vulkan_backend_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/render/devices.h"
#include "backend_compare.h"
#include "core/image/image_error.h"
#include "core/loaders/scene_loader.h"
#include "core/system/error.h"
#include "core/scene/camera_path.h"
#include "shared/eye_trace.h"
#include "test_render.h"
#include "test_util.h"

namespace photon {
namespace {

constexpr double kFrameSeconds = 1.0 / 60.0;
const CameraPath kOrbit{20.0};  // 0.3° a frame

RenderSettings movingSettings() {
    RenderSettings s = test::sizedSettings({}, 80, 60, 20000);
    s.estimator = Estimator::Sppm;
    s.denoise = Denoise::On;
    s.reproject = true;
    s.seed = 5;
    return s;
}

// `frames` frames still, then `moves` frames each a step further along the orbit.
std::unique_ptr<Renderer> renderMoving(const Scene& scene, const RenderSettings& settings, std::uint32_t frames,
                                      std::uint32_t moves) {
    auto backend = createRenderer("cpu");
    test::renderFrames(*backend, scene, settings, frames);
    for (std::uint32_t f = 1; f <= moves; ++f) {
        backend->moveCamera(cameraAt(kOrbit, scene.camera, f * kFrameSeconds));
        backend->renderFrame();
    }
    return backend;
}

std::vector<float> historyLengths(Renderer& backend) {
    std::vector<float> frames;
    for (const PixelAov& a : backend.readAovs()) {
        frames.push_back(a.frames);
    }
    return frames;
}

TEST(Reproject, AStillCameraRendersAsWithout) {
    Scene scene = defaultScene();
    RenderSettings on = movingSettings();
    RenderSettings off = on;
    off.reproject = false;
    auto a = renderMoving(scene, on, 6, 0);
    auto b = renderMoving(scene, off, 6, 0);
    EXPECT_EQ(test::differingPixels(a->rawImage(), b->rawImage()), 0u);
    EXPECT_EQ(test::differingPixels(a->image(), b->image()), 0u);
    for (float f : historyLengths(*a)) {
        ASSERT_EQ(f, 6.0f);
    }
}

// Every pixel against the rule, worked out here from the hit points: where the surface a pixel
// sees (along its centre ray, at its path's length) lay in the frame before; a pixel whose surface
// lay outside the previous view starts again (1 frame), and nearly every pixel whose surface lay
// inside, away from the border, keeps all 8 frames before this one.
TEST(Reproject, APixelKeepsItsHistoryWhereItsSurfaceStaysInView) {
    Scene scene = defaultScene();
    RenderSettings s = movingSettings();
    // A narrow view filled with the box's walls, and a long step (3°), so that walls come into
    // view at the image's side.
    scene.camera.fovY = 20.0f;
    const CameraDesc moved = cameraAt(CameraPath{120.0}, scene.camera, 1.0);
    auto backend = createRenderer("cpu");
    test::renderFrames(*backend, scene, s, 8);
    backend->moveCamera(moved);
    backend->renderFrame();
    std::vector<float> frames = historyLengths(*backend);
    std::vector<HitPoint> hits = backend->readHitPoints();
    Camera now = makeCamera(moved, s.width, s.height);
    Camera before = makeCamera(scene.camera, s.width, s.height);
    std::size_t inside = 0, kept = 0, outside = 0, background = 0;
    for (std::uint32_t p = 0; p < hits.size(); ++p) {
        const HitPoint& hp = hits[p];
        if (!(hp.pathLength > 0.0f)) {
            ++background;
            continue;
        }
        Rng unused = rngCreate(p, 0u, 0u, STREAM_CAMERA);
        Ray ray = cameraRay(now, p % s.width, p / s.width, s.width, s.height, FLAG_PIXEL_CENTER, unused);
        glm::vec3 q = projectToPixel(before, ray.origin + ray.direction * hp.pathLength, s.width, s.height);
        if (q.x < -0.5f || q.y < -0.5f || q.x >= float(s.width) + 0.5f || q.y >= float(s.height) + 0.5f) {
            ++outside;
            EXPECT_EQ(frames[p], 1.0f) << "pixel " << p << " came into view";
        } else if (q.x >= 1.0f && q.y >= 1.0f && q.x < float(s.width) - 1.0f && q.y < float(s.height) - 1.0f) {
            ++inside;
            kept += frames[p] == 9.0f ? 1 : 0;
        }
    }
    std::printf("%zu pixels' surfaces lay inside the previous view, %zu kept 9 frames; %zu came into view; %zu "
                "without a surface\n",
                inside, kept, outside, background);
    EXPECT_GT(outside, 0u) << "the orbit brings pixels into view";
    // Those that start again although inside: across edges, where the pixel's frames saw another
    // surface than this frame's path.
    EXPECT_GE(double(kept), 0.9 * double(inside));
}

// While moving, the carried image is nearer the converged image at the final camera than the
// frame alone (what a restart shows), raw and denoised.
TEST(Reproject, TheCarriedImageIsCloserToTheReferenceThanARestart) {
    Scene scene = defaultScene();
    RenderSettings s = movingSettings();
    const std::uint32_t moves = 12;
    CameraDesc last = cameraAt(kOrbit, scene.camera, moves * kFrameSeconds);
    RenderSettings still = s;
    still.denoise = Denoise::Off;
    still.reproject = false;
    still.photons = 100000;
    still.seed = 11;
    auto reference = createRenderer("cpu");
    reference->setScene(scene);
    reference->setSettings(still);
    reference->setCamera(last);
    for (int f = 0; f < 96; ++f) {
        reference->renderFrame();
    }
    Image truth = reference->rawImage();
    RenderSettings restart = s;
    restart.reproject = false;
    auto carried = renderMoving(scene, s, 1, moves);
    auto restarted = renderMoving(scene, restart, 1, moves);
    QualityMasks masks(truth);
    Quality carriedRaw = measureQuality(carried->rawImage(), truth, masks);
    Quality carriedDenoised = measureQuality(carried->image(), truth, masks);
    Quality restartRaw = measureQuality(restarted->rawImage(), truth, masks);
    Quality restartDenoised = measureQuality(restarted->image(), truth, masks);
    std::printf("away from the focus: restart %.2f%% raw, %.2f%% denoised; carried %.2f%% raw, %.2f%% denoised\n",
                100 * restartRaw.away, 100 * restartDenoised.away, 100 * carriedRaw.away, 100 * carriedDenoised.away);
    EXPECT_LT(carriedRaw.away, 0.8 * restartRaw.away);
    EXPECT_LT(carriedDenoised.away, 0.8 * restartDenoised.away);
    EXPECT_LT(carriedDenoised.away, restartRaw.away);
    EXPECT_TRUE(allFinite(carried->image()));
}

TEST(Reproject, LightsAndSettingsStillRestart) {
    Scene scene = defaultScene();
    RenderSettings s = movingSettings();
    auto backend = renderMoving(scene, s, 4, 1);
    s.seed += 1;
    backend->setSettings(s);
    backend->moveCamera(cameraAt(kOrbit, scene.camera, 2 * kFrameSeconds));
    backend->renderFrame();
    for (float f : historyLengths(*backend)) {
        ASSERT_EQ(f, 1.0f);
    }
    backend->renderFrame();
    backend->setScene(scene);
    backend->moveCamera(cameraAt(kOrbit, scene.camera, 3 * kFrameSeconds));
    backend->renderFrame();
    for (float f : historyLengths(*backend)) {
        ASSERT_EQ(f, 1.0f);
    }
}

TEST(Reproject, WithoutReprojectAMoveRestarts) {
    Scene scene = defaultScene();
    RenderSettings s = movingSettings();
    s.reproject = false;
    auto backend = renderMoving(scene, s, 4, 1);
    EXPECT_EQ(backend->accumulatedFrames(), 1u);
    for (float f : historyLengths(*backend)) {
        ASSERT_EQ(f, 1.0f);
    }
}

TEST(CameraPath, AnOrbitKeepsDistanceAndHeightAndCloses) {
    CameraDesc start;
    start.position = glm::vec3(1.0f, 2.0f, 5.0f);
    start.lookAt = glm::vec3(0.5f, 1.0f, 0.0f);
    CameraPath path = parseCameraPath("orbit:4", "--camera-path");
    for (double t : {0.3, 1.0, 2.7}) {
        CameraDesc c = cameraAt(path, start, t);
        EXPECT_NEAR(glm::length(c.position - c.lookAt), glm::length(start.position - start.lookAt), 1e-5);
        EXPECT_NEAR(c.position.y, start.position.y, 1e-5);
    }
    CameraDesc half = cameraAt(path, start, 2.0);
    EXPECT_NEAR(half.position.x, 0.0f, 1e-5);  // opposite side of the target
    EXPECT_NEAR(half.position.z, -5.0f, 1e-5);
    CameraDesc full = cameraAt(path, start, 4.0);
    EXPECT_NEAR(glm::length(full.position - start.position), 0.0f, 1e-5);
    for (const char* bad : {"orbit", "orbit:", "orbit:0", "orbit:-3", "orbit:nan", "spin:4", "orbit:4s", ""}) {
        EXPECT_THROW(parseCameraPath(bad, "--camera-path"), InputError) << bad;
    }
}

}  // namespace
}  // namespace photon
