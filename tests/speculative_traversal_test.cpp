// CUDA's speculative traversal (traceWideSpeculative, shared/intersect.h) against the one-loop
// traversal every other backend runs, on the CPU. A lane alone would test each leaf as soon as it
// met it, which is the one loop again; here the vote says that the rest of the warp is always
// still searching, so the lane speculates as far as it can (on past its leaf until a second one,
// through nodes a hit has since put out of reach), the most that a lane of a real warp can do.
// The hits must still be the one loop's, bit for bit.
#define PH_ANY_LANE(condition) ((void)(condition), true)

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "core/loaders/scene_loader.h"
#include "shared/intersect.h"
#include "test_util.h"
#include "tools/bench_scenes.h"

namespace photon {
namespace {

// Random rays (test::randomSceneRays); returns those whose results differ (-1: the scene has no
// hierarchy).
int compareTraversals(const Scene& scene, int rays, std::uint32_t seed) {
    test::SceneBindings sb(scene);
    const Bindings& b = sb.bindings;
    if (b.params.scene.bvhNodeCount == 0u) {
        return -1;
    }
    int differing = 0;
    std::vector<Ray> all = test::randomSceneRays(sb.scene, rays, seed);
    for (std::size_t i = 0; i < all.size(); ++i) {
        const Ray& ray = all[i];
        RayFrame frame = makeRayFrame(ray);
        for (uint query : {QUERY_CLOSEST, QUERY_ANY}) {
            TraceResult one{ray.tMax, NONE, NONE, 0.0f, 0.0f};
            TraceResult warp = one;
            bool answered = traceWide(b, ray, frame, query, one);
            bool warpAnswered = traceWideSpeculative(b, ray, frame, query, warp);
            if (warpAnswered != answered || std::memcmp(&one, &warp, sizeof one) != 0) {
                if (differing < 5) {
                    ADD_FAILURE() << "ray " << i << " query " << query << ": one loop kind " << one.kind << " index "
                                  << one.index << " t " << one.t << "; speculative kind " << warp.kind << " index "
                                  << warp.index << " t " << warp.t;
                }
                differing += 1;
            }
        }
    }
    return differing;
}

TEST(SpeculativeTraversal, FindsTheOneLoopsHitsOnMeshes) {
    for (std::uint64_t triangles : {200u, 20000u, 300000u}) {
        SCOPED_TRACE(std::to_string(triangles) + " triangles");
        EXPECT_EQ(compareTraversals(tools::meshBenchScene(triangles, triangles == 20000u), 4000, 3), 0);
    }
}

TEST(SpeculativeTraversal, FindsTheOneLoopsHitsOnEveryShippedScene) {
    int withHierarchy = 0;
    for (const std::string& path : test::shippedScenes({".json", ".glb", ".gltf"})) {
        SCOPED_TRACE(path);
        int differing = compareTraversals(loadSceneFile(path), 4000, 5);
        EXPECT_LE(differing, 0);
        withHierarchy += differing == 0 ? 1 : 0;
    }
    EXPECT_GE(withHierarchy, 3);  // bunny.json, mirrors.json, textured.glb at least
}

}  // namespace
}  // namespace photon
