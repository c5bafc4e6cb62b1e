// Renders with known answers made of triangles, on the CPU backend (known_answers.h):
//   furnace:   a tessellated closed diffuse sphere around a point light; the mean radiance of any
//              closed Lambertian enclosure is ρΦ / (π(1−ρ)A), so the sphere's value ρΦ/(4π²R²(1−ρ))
//              holds to within the tessellation's area error;
//   ball lens: a glass sphere of 200k triangles with smooth normals focuses a parallel beam at
//              nR / (2(n−1)) from its centre, as the analytic sphere does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "core/render/devices.h"
#include "core/loaders/model_loader.h"
#include "known_answers.h"
#include "test_util.h"
#include "tools/mesh_shapes.h"

namespace photon {
namespace {

using test::kPi;

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
        RenderSettings s = test::sizedSettings(scene.render, 32, 24, 5000);
        s.view = View::Direct;
        Image image = test::renderOnCpu(scene, s);
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
    Scene s = test::furnaceScene(rho, phi, [&](Scene& scene, std::uint32_t wall) {
        Mesh mesh = tools::uvSphere(glm::vec3(0.0f), R, 48, 96, true);
        mesh.materials.assign(mesh.triangles.size(), wall);
        scene.addMesh(mesh, glm::mat4(1.0f));
    });
    double tessellation = 4.0 * kPi * R * R / meshArea(s) - 1.0;
    RenderSettings settings = test::furnaceSettings(Estimator::Radius);
    Image image = test::renderOnCpu(s, settings, settings.frames);
    double expected = test::furnaceRadiance(R, rho, phi);
    double mean = test::meanRed(image);
    std::printf("tessellated furnace (%zu triangles): mean/expected %.4f, tessellation area error %.4f\n",
                s.triangles.size(), mean / expected, tessellation);
    EXPECT_NEAR(mean / expected, 1.0, 0.01 + std::abs(tessellation));
}

TEST(MeshBallLens, SmoothTessellatedSphereFocusesAtTheParaxialFocus) {
    const float n = 1.5f;
    const double focus = test::paraxialFocus(n);
    const float probe = 0.001f;
    // The sphere of 200k triangles is built once; the search copies it for each screen position.
    Scene lens = test::ballLensScene(n, [](Scene& s, std::uint32_t glass) {
        Mesh sphere = tools::uvSphere(glm::vec3(0.0f), 1.0f, 224, 448, true);
        sphere.materials.assign(sphere.triangles.size(), glass);
        s.addMesh(sphere, glm::mat4(1.0f));
    });
    ASSERT_GE(lens.triangles.size(), 100000u);
    test::CausticPeak peak = test::findCausticPeak(lens, probe);
    std::printf("tessellated ball lens (%zu triangles): caustic peak at z = %.3f, paraxial focus %.3f\n",
                lens.triangles.size(), peak.z, focus);
    test::expectPeakAtFocus(peak, focus);
}

}  // namespace
}  // namespace photon
