// Renders with known answers made of triangles, on the CPU backend:
//   furnace:   a tessellated closed diffuse sphere around a point light; the mean radiance of any
//              closed Lambertian enclosure is ρΦ / (π(1−ρ)A), so the sphere's value ρΦ/(4π²R²(1−ρ))
//              holds to within the tessellation's area error;
//   ball lens: a glass sphere of 200k triangles with smooth normals focuses a parallel beam at
//              nR / (2(n−1)) from its centre, as the analytic sphere does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "apps/backends.h"
#include "core/loaders/model_loader.h"
#include "test_util.h"
#include "tools/mesh_shapes.h"

namespace photon {
namespace {

constexpr double kPi = 3.14159265358979323846;

double meshArea(const Scene& s) {
    double area = 0.0;
    for (const Triangle& t : s.triangles) {
        area += 0.5 * double(glm::length(glm::cross(t.v1 - t.v0, t.v2 - t.v0)));
    }
    return area;
}

// A model file rendered by itself gets a camera and lights that show it, whichever way a flat
// model faces: the sun over the camera's shoulder alone lit the far side of a square seen at an
// angle (assimp's concave_polygon.obj and regr_3429812.obj rendered black).
TEST(ModelScene, FlatModelsAreLitOnTheSideTheCameraSees) {
    for (float nx : {1.0f, -1.0f}) {
        std::string path = test::testOutputPath(nx > 0 ? "flat-x.obj" : "flat-minus-x.obj");
        {
            std::ofstream obj(path);
            // A unit square in the plane x = 0, wound to face +x or -x (OBJ has no back faces,
            // but the winding picks the geometric normal).
            obj << "v 0 0 0\nv 0 1 0\nv 0 1 1\nv 0 0 1\n" << (nx > 0 ? "f 1 2 3 4\n" : "f 4 3 2 1\n");
        }
        Scene scene = loadModelScene(path);
        RenderSettings s = scene.render;
        s.width = 32;
        s.height = 24;
        s.photons = 5000;
        s.view = View::Direct;
        auto backend = createBackend("cpu");
        backend->setScene(scene);
        backend->setSettings(s);
        backend->renderFrame();
        Image image = backend->image();
        std::size_t lit = 0;
        for (const glm::vec4& p : image.pixels) {
            lit += p.x > 0.0f ? 1u : 0u;
        }
        EXPECT_GT(lit, image.pixels.size() / 20) << path << ": the square seen at an angle covers about a tenth";
    }
}

TEST(MeshFurnace, TessellatedSphereWithinOnePercentPlusItsTessellation) {
    const float R = 2.0f;
    const float rho = 0.5f;
    const float phi = 10.0f;
    Scene s;
    std::uint32_t wall = s.addMaterial("wall", makeDiffuse(glm::vec3(rho)));
    Mesh mesh = tools::uvSphere(glm::vec3(0.0f), R, 48, 96, true);
    mesh.materials.assign(mesh.triangles.size(), wall);
    s.addMesh(mesh, glm::mat4(1.0f));
    s.addPointLight(glm::vec3(0.0f), glm::vec3(phi));
    s.camera.position = glm::vec3(0.0f);
    s.camera.lookAt = glm::vec3(0.3f, 0.2f, -1.0f);
    s.camera.fovY = 90.0f;
    s.finalize();
    double tessellation = 4.0 * kPi * R * R / meshArea(s) - 1.0;
    RenderSettings settings;
    settings.width = 48;
    settings.height = 48;
    settings.photons = 200000;
    settings.frames = 4;
    settings.estimator = Estimator::Radius;
    settings.radius = 0.15f;
    settings.maxPhotonDepth = 64;
    auto backend = createBackend("cpu");
    backend->setScene(s);
    backend->setSettings(settings);
    for (std::uint32_t f = 0; f < settings.frames; ++f) {
        backend->renderFrame();
    }
    Image image = backend->image();
    double expected = rho * phi / (4.0 * kPi * kPi * R * R * (1.0 - rho));
    double mean = 0.0;
    for (const glm::vec4& p : image.pixels) {
        mean += p.x;
    }
    mean /= double(image.pixels.size());
    std::printf("tessellated furnace (%zu triangles): mean/expected %.4f, tessellation area error %.4f\n",
                s.triangles.size(), mean / expected, tessellation);
    EXPECT_NEAR(mean / expected, 1.0, 0.01 + std::abs(tessellation));
}

TEST(MeshBallLens, SmoothTessellatedSphereFocusesAtTheParaxialFocus) {
    const float n = 1.5f;
    const double focus = n / (2.0 * (n - 1.0));
    const float probe = 0.001f;
    // One scene per screen position; the sphere of 200k triangles is built once and copied.
    Scene base;
    std::uint32_t glass = base.addMaterial("glass", makeGlass(n, glm::vec3(1.0f)));
    std::uint32_t white = base.addMaterial("white", makeDiffuse(glm::vec3(0.8f)));
    Mesh sphere = tools::uvSphere(glm::vec3(0.0f), 1.0f, 224, 448, true);
    sphere.materials.assign(sphere.triangles.size(), glass);
    base.addMesh(sphere, glm::mat4(1.0f));
    ASSERT_GE(base.triangles.size(), 100000u);
    float distance = 1000.0f;
    float angle = float(std::atan(0.1 / distance) * 180.0 / kPi);
    base.addSpotLight(glm::vec3(0.0f, 0.0f, -distance), glm::vec3(0, 0, 1), glm::vec3(1.0f), angle, angle);
    base.camera.position = glm::vec3(3.0f, 0.0f, 0.0f);
    base.camera.lookAt = glm::vec3(0.0f);
    double bestZ = 0.0;
    double bestDensity = -1.0;
    auto backend = createBackend("cpu");
    for (int i = 0; i <= 40; ++i) {
        float z = 1.40f + 0.005f * float(i);
        Scene s = base;
        s.addQuad(glm::vec3(-2.0f, -2.0f, z), glm::vec3(4, 0, 0), glm::vec3(0, 4, 0), white);
        s.finalize();
        RenderSettings settings;
        settings.width = 4;
        settings.height = 4;
        settings.photons = 200000;
        settings.causticFraction = 0.99f;
        settings.causticRadius = probe;
        backend->setScene(std::move(s));
        backend->setSettings(settings);
        backend->renderFrame();
        PhotonMaps maps = backend->readPhotonMaps();
        double density = 0.0;
        for (const Photon& p : maps.photons[MAP_CAUSTIC]) {
            if (p.position.x * p.position.x + p.position.y * p.position.y < probe * probe) {
                density += p.power.x;
            }
        }
        if (density > bestDensity) {
            bestDensity = density;
            bestZ = z;
        }
    }
    std::printf("tessellated ball lens (%zu triangles): caustic peak at z = %.3f, paraxial focus %.3f\n",
                base.triangles.size(), bestZ, focus);
    EXPECT_GT(bestDensity, 0.0);
    EXPECT_NEAR(bestZ / focus, 1.0, 0.02);
}

}  // namespace
}  // namespace photon
