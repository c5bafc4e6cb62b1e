// The viewer's camera controller and light editor: plain math on CameraDesc and Scene, checked
// without a window.
#include <gtest/gtest.h>

#include <cmath>

#include "core/loaders/scene_loader.h"
#include "shared/light_types.h"
#include "viewer/camera_controller.h"
#include "viewer/hud.h"
#include "viewer/light_editor.h"
#include "test_util.h"

namespace photon::viewer {
namespace {

CameraDesc cornellCamera() {
    CameraDesc c;
    c.position = glm::vec3(0.0f, 1.0f, 3.9f);
    c.lookAt = glm::vec3(0.0f, 1.0f, 0.0f);
    c.fovY = 38.0f;
    return c;
}

void expectNear(glm::vec3 a, glm::vec3 b, float tolerance) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(CameraController, OrbitKeepsTargetAndDistanceAndUndoes) {
    CameraController c(cornellCamera(), 3.5f);
    c.orbit(glm::vec2(120.0f, -40.0f), 600.0f);
    expectNear(c.camera().lookAt, glm::vec3(0.0f, 1.0f, 0.0f), 1e-6f);
    EXPECT_NEAR(c.distance(), 3.9f, 1e-4f);
    EXPECT_LT(c.camera().position.x, -0.5f);  // the scene turns with the mouse, the camera the other way
    c.orbit(glm::vec2(0.0f, 40.0f), 600.0f);
    c.orbit(glm::vec2(-120.0f, 0.0f), 600.0f);
    expectNear(c.camera().position, glm::vec3(0.0f, 1.0f, 3.9f), 1e-4f);
}

TEST(CameraController, PitchStopsShortOfThePoles) {
    CameraController c(cornellCamera(), 3.5f);
    for (int i = 0; i < 50; ++i) {
        c.orbit(glm::vec2(0.0f, 200.0f), 600.0f);  // far past straight above
    }
    glm::vec3 offset = glm::normalize(c.camera().position - c.camera().lookAt);
    EXPECT_GT(offset.y, 0.99f);
    EXPECT_LT(offset.y, std::cos(0.5f * 3.14159265f / 180.0f));  // at least 0.5° from the pole
    for (int i = 0; i < 50; ++i) {
        c.look(glm::vec2(0.0f, -300.0f), 600.0f);  // looking up past vertical
    }
    glm::vec3 forward = glm::normalize(c.camera().lookAt - c.camera().position);
    EXPECT_LT(forward.y, 1.0f - 1e-5f);
    EXPECT_TRUE(std::isfinite(forward.x) && std::isfinite(forward.z));
}

TEST(CameraController, LookKeepsPositionPanKeepsDirection) {
    CameraController c(cornellCamera(), 3.5f);
    c.look(glm::vec2(100.0f, 30.0f), 600.0f);
    expectNear(c.camera().position, glm::vec3(0.0f, 1.0f, 3.9f), 1e-6f);
    glm::vec3 forward = glm::normalize(c.camera().lookAt - c.camera().position);
    EXPECT_GT(forward.x, 0.1f);  // dragging right looks right
    EXPECT_LT(forward.y, -0.01f);  // dragging down looks down
    CameraController p(cornellCamera(), 3.5f);
    p.pan(glm::vec2(-300.0f, 0.0f), 600.0f);  // half the window's height to the left: the scene follows
    expectNear(p.camera().lookAt - p.camera().position, glm::vec3(0.0f, 0.0f, -3.9f), 1e-5f);
    float halfHeight = 3.9f * std::tan(0.5f * 38.0f * 3.14159265f / 180.0f);
    EXPECT_NEAR(p.camera().position.x, halfHeight, 1e-4f);
}

TEST(CameraController, ZoomApproachesTheTargetAndFlyMovesBoth) {
    CameraController c(cornellCamera(), 3.5f);
    c.zoom(1.0f);
    EXPECT_NEAR(c.distance(), 3.9f * 0.9f, 1e-5f);
    c.zoom(-2.0f);
    EXPECT_NEAR(c.distance(), 3.9f / 0.9f, 1e-4f);
    c.zoom(1000.0f);
    EXPECT_GT(c.distance(), 0.0f);  // never through the target
    CameraController f(cornellCamera(), 3.5f);
    FlyInput forward;
    forward.forward = 1.0f;
    f.fly(forward, 0.5f, 0.2f);  // 0.2 diagonals a second for half a second: 0.35 units
    expectNear(f.camera().position, glm::vec3(0.0f, 1.0f, 3.9f - 0.35f), 1e-5f);
    expectNear(f.camera().lookAt, glm::vec3(0.0f, 1.0f, -0.35f), 1e-5f);
    FlyInput up;
    up.up = 1.0f;
    f.fly(up, 1.0f, 0.1f);
    EXPECT_NEAR(f.camera().position.y, 1.35f, 1e-5f);
}

TEST(LightEditor, MovesLightsAndTheirSurfacesWithoutDrift) {
    Scene s;
    std::uint32_t white = s.addMaterial("white", makeDiffuse(glm::vec3(0.7f)));
    s.addQuad(glm::vec3(-1, 0, -1), glm::vec3(0, 0, 2), glm::vec3(2, 0, 0), white);
    s.addPointLight(glm::vec3(0, 1.5f, 0), glm::vec3(10.0f));
    s.addSphereLight(glm::vec3(0.5f, 1.0f, 0.0f), 0.1f, glm::vec3(5.0f));
    s.addQuadLight(glm::vec3(-0.2f, 1.9f, -0.2f), glm::vec3(0.4f, 0, 0), glm::vec3(0, 0, 0.4f), glm::vec3(5.0f));
    s.finalize();
    LightEditor editor(s);
    ASSERT_EQ(editor.lightCount(), 3u);
    EXPECT_EQ(editor.lightName(1), "sphere 1");
    for (int i = 0; i < 1000; ++i) {
        editor.move(1, glm::vec3(0.001f, 0.0f, 0.0f));
    }
    editor.setPosition(2, glm::vec3(0.0f, 1.5f, 0.0f));
    Scene moved = editor.scene();
    expectNear(moved.lights[1].position, glm::vec3(1.5f, 1.0f, 0.0f), 1e-4f);
    expectNear(moved.spheres.back().center, glm::vec3(1.5f, 1.0f, 0.0f), 1e-4f);  // its visible sphere
    expectNear(moved.quads.back().corner, glm::vec3(0.0f, 1.5f, 0.0f), 1e-6f);     // the quad light's surface
    expectNear(moved.lights[0].position, glm::vec3(0, 1.5f, 0), 0.0f);             // untouched
    expectNear(moved.quads.front().corner, glm::vec3(-1, 0, -1), 0.0f);            // the floor stays
    EXPECT_GE(moved.boundsMax.x, 1.6f - 1e-4f);                                   // finalized again
    editor.reset();
    expectNear(editor.scene().lights[1].position, glm::vec3(0.5f, 1.0f, 0.0f), 0.0f);
}

// Every type can be moved: a directional light turns to shine from its moved point, the
// emissive triangles move together, and the background's radiance is edited.
TEST(LightEditor, EditsEveryLightType) {
    Scene s;
    std::uint32_t white = s.addMaterial("white", makeDiffuse(glm::vec3(0.7f)));
    Material glow = makeDiffuse(glm::vec3(0.5f));
    glow.emission = glm::vec3(2.0f);
    std::uint32_t panel = s.addMaterial("panel", glow);
    s.addQuad(glm::vec3(-1, 0, -1), glm::vec3(0, 0, 2), glm::vec3(2, 0, 0), white);
    s.addTriangle(glm::vec3(0, 1, 0), glm::vec3(0.2f, 1, 0), glm::vec3(0, 1, 0.2f), panel);
    s.addSpotLight(glm::vec3(0, 1.5f, 0), glm::vec3(0, -1, 0), glm::vec3(10.0f), 30.0f, 20.0f);
    s.addDirectionalLight(glm::vec3(0, -1, 0), glm::vec3(1.0f));
    s.finalize();
    LightEditor editor(s);
    ASSERT_EQ(editor.lightCount(), 3u);
    EXPECT_EQ(editor.lightName(0), "spot 0");
    EXPECT_EQ(editor.lightName(1), "directional 1");
    EXPECT_EQ(editor.lightName(2), "emissive triangles 2");

    // The sun's point lies above the scene; moved sideways, the light tilts.
    glm::vec3 sun = editor.position(1);
    EXPECT_GT(sun.y, s.boundsMax.y);
    editor.setPosition(1, sun + glm::vec3(sun.y - 0.5f * (s.boundsMin.y + s.boundsMax.y), 0, 0));
    editor.move(2, glm::vec3(0, 0.5f, 0));
    editor.setEnvironmentRadiance(glm::vec3(0.1f, 0.2f, 0.3f));
    Scene moved = editor.scene();
    glm::vec3 axis = directionalDirection(moved.lights[1]);
    EXPECT_LT(axis.x, -0.5f);
    EXPECT_LT(axis.y, -0.5f);
    expectNear(moved.triangles.back().v0, glm::vec3(0, 1.5f, 0), 1e-6f);  // the emissive triangle
    expectNear(moved.quads.front().corner, glm::vec3(-1, 0, -1), 0.0f);    // the floor stays
    EXPECT_EQ(moved.lights[2].type, LIGHT_TRIANGLES);
    expectNear(environmentScale(moved.infiniteLights[0]), glm::vec3(0.1f, 0.2f, 0.3f), 0.0f);

    editor.reset();
    Scene back = editor.scene();
    expectNear(directionalDirection(back.lights[1]), glm::vec3(0, -1, 0), 0.0f);
    expectNear(back.triangles.back().v0, glm::vec3(0, 1, 0), 0.0f);
    expectNear(environmentScale(back.infiniteLights[0]), glm::vec3(0.0f), 0.0f);
}

// A map's intensity and turn about the vertical: the light that samples it and the one that rays
// that leave the scene see change together, on top of the scene's own rotation.
TEST(LightEditor, TurnsAndDimsTheEnvironment) {
    Scene s;
    s.addSphere(glm::vec3(0.0f), 1.0f, s.addMaterial("white", makeDiffuse(glm::vec3(0.7f))));
    EnvironmentLight env;
    env.map.width = 4;
    env.map.height = 2;
    env.map.texels.assign(8, glm::vec3(1.0f));
    env.radiance = glm::vec3(2.0f);
    env.rotation = environmentRotation(90.0f, glm::vec3(1, 0, 0));
    env.lights = true;
    s.setEnvironment(env);
    s.finalize();
    LightEditor editor(s);
    ASSERT_TRUE(editor.environmentIsMap());
    EXPECT_EQ(editor.environmentRadiance(), glm::vec3(2.0f));
    editor.setEnvironmentRadiance(glm::vec3(0.5f));
    editor.setEnvironmentTurn(90.0f);
    Scene turned = editor.scene();
    ASSERT_NE(turned.environmentLight, NONE);
    const Light& l = turned.lights[turned.environmentLight];
    expectNear(environmentScale(l), glm::vec3(0.5f), 0.0f);
    expectNear(environmentScale(turned.infiniteLights[0]), glm::vec3(0.5f), 0.0f);
    // The map's x axis, turned by 90° about X first (unchanged), then 90° about +Y: −Z.
    expectNear(environmentMapX(l), glm::vec3(0, 0, -1), 1e-6f);
    EXPECT_LT(turned.lights[turned.environmentLight].power.x, s.lights[s.environmentLight].power.x);
    editor.reset();
    expectNear(environmentMapX(editor.scene().lights[0]), glm::vec3(1, 0, 0), 1e-6f);
}

// A medium's density scales its coefficients and its g is replaced; reset brings the file's back.
TEST(LightEditor, EditsTheMediaDensityAndG) {
    Scene fog = loadSceneFile(test::scenesDir() + "/fog.json");
    LightEditor editor(fog);
    ASSERT_EQ(editor.mediumCount(), 1u);
    EXPECT_EQ(editor.mediumDensity(0), 1.0f);
    EXPECT_EQ(editor.mediumG(0), fog.media[0].g);
    editor.setMediumDensity(0, 4.0f);
    editor.setMediumG(0, -0.5f);
    Scene edited = editor.scene();
    EXPECT_EQ(edited.media[0].scattering, 4.0f * fog.media[0].scattering);
    EXPECT_EQ(edited.media[0].absorption, 4.0f * fog.media[0].absorption);
    EXPECT_EQ(edited.media[0].g, -0.5f);
    EXPECT_EQ(edited.media[0].lower, fog.media[0].lower);
    editor.reset();
    EXPECT_EQ(editor.scene().media[0].scattering, fog.media[0].scattering);
    EXPECT_EQ(editor.scene().media[0].g, fog.media[0].g);
}

TEST(LightEditor, CornellLightMovesWithTheScene) {
    LightEditor editor(defaultScene());
    ASSERT_EQ(editor.lightCount(), 1u);
    editor.move(0, glm::vec3(0.3f, -0.2f, 0.1f));
    expectNear(editor.scene().lights[0].position, glm::vec3(0.3f, 1.76f, 0.1f), 1e-6f);
}

// The settings panel of the default 640×480 window: at most 36% of its width, within its height,
// the long Render section closed (issue 38: open, it covered 55% and was cut off at the bottom).
TEST(Hud, PanelFitsTheWindow) {
    HudLayout small = hudLayout(640.0f, 480.0f);
    EXPECT_LE(small.width, 0.4f * 640.0f);
    EXPECT_LE(small.maxHeight, 480.0f - 16.0f);
    EXPECT_FALSE(small.renderOpen);
    HudLayout large = hudLayout(1920.0f, 1080.0f);
    EXPECT_FLOAT_EQ(large.width, 340.0f);
    EXPECT_TRUE(large.renderOpen);
    EXPECT_GE(hudLayout(100.0f, 50.0f).maxHeight, 100.0f) << "a tiny window still gets a panel that scrolls";
}

}  // namespace
}  // namespace photon::viewer
