// The bounding volume hierarchy against brute force: the nearest hit of random rays, and whether
// shadow rays are blocked, equal testing every primitive one by one, over random triangle soups
// (with spheres, quads and planes among them), over every shipped scene and at the ends of the
// float range. And the hierarchy's shape: every primitive in exactly one leaf, every child's
// quantized box holding its primitives.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <random>

#include "core/loaders/scene_loader.h"
#include "core/system/parallel.h"
#include "shared/intersect.h"
#include "test_util.h"
#include "tools/bench_scenes.h"

namespace photon {
namespace {

// The nearest hit by testing every primitive (the traversal's reference).
TraceResult bruteForce(const Scene& scene, const Bindings& b, const Ray& ray) {
    TraceResult r;
    r.t = ray.tMax;
    r.kind = NONE;
    r.index = NONE;
    RayFrame frame = makeRayFrame(ray);
    for (uint i = 0; i < b.params.scene.planeCount; ++i) {
        float t = intersectPlane(ray, b.planes[i].normal, b.planes[i].offset, r.t);
        if (t < r.t) {
            r = {t, PRIM_PLANE, i, 0.0f, 0.0f};
        }
    }
    uint counts[3] = {uint(scene.spheres.size()), uint(scene.quads.size()), uint(scene.triangles.size())};
    uint kinds[3] = {PRIM_SPHERE, PRIM_QUAD, PRIM_TRIANGLE};
    for (int k = 0; k < 3; ++k) {
        for (uint i = 0; i < counts[k]; ++i) {
            float b1;
            float b2;
            float t = intersectPrimitive(b, (kinds[k] << PRIMITIVE_INDEX_BITS) | i, ray, frame, r.t, b1, b2);
            if (t < r.t) {
                r = {t, kinds[k], i, b1, b2};
            }
        }
    }
    return r;
}

// Random rays from inside and around the scene's bounds; returns the rays whose hits differ.
int compareWithBruteForce(const Scene& scene, int rays, std::uint32_t seed) {
    test::SceneBindings sb(scene);
    const Bindings& b = sb.bindings;
    int differing = 0;
    std::vector<Ray> all = test::randomSceneRays(sb.scene, rays, seed);
    for (std::size_t i = 0; i < all.size(); ++i) {
        const Ray& ray = all[i];
        TraceResult expected = bruteForce(sb.scene, b, ray);
        TraceResult actual = traceRay(b, ray, QUERY_CLOSEST);
        bool any = traceRay(b, ray, QUERY_ANY).kind != NONE;
        bool same = actual.kind == expected.kind && actual.t == expected.t &&
                    (actual.index == expected.index || actual.t == expected.t);
        if (!same || any != (expected.kind != NONE)) {
            if (differing < 5) {
                ADD_FAILURE() << "ray " << i << ": traversal kind " << actual.kind << " index " << actual.index << " t "
                              << actual.t << "; brute force kind " << expected.kind << " index " << expected.index
                              << " t " << expected.t << "; any " << any;
            }
            differing += 1;
        }
    }
    return differing;
}

// Triangles, a few spheres and quads and a plane in a cube of side 2 about the origin, the whole
// scene then moved by x → scale · x + offset.
Scene randomSoup(std::size_t triangles, std::uint32_t seed, float scale = 1.0f, glm::vec3 offset = glm::vec3(0.0f)) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Scene s;
    std::uint32_t m = s.addMaterial("m", makeDiffuse(glm::vec3(0.5f)));
    Mesh mesh;
    for (std::size_t i = 0; i < triangles; ++i) {
        glm::vec3 c(u(random), u(random), u(random));
        float size = 0.02f + 0.3f * std::abs(u(random)) * std::abs(u(random));
        for (int k = 0; k < 3; ++k) {
            mesh.positions.push_back(c + size * glm::vec3(u(random), u(random), u(random)));
        }
        auto v = std::uint32_t(3 * i);
        mesh.triangles.emplace_back(v, v + 1, v + 2);
        mesh.materials.push_back(m);
    }
    s.addMesh(mesh, glm::mat4(glm::vec4(scale, 0, 0, 0), glm::vec4(0, scale, 0, 0), glm::vec4(0, 0, scale, 0),
                              glm::vec4(offset, 1.0f)));
    for (int i = 0; i < 5; ++i) {
        glm::vec3 c(u(random), u(random), u(random));
        float r = 0.1f + 0.2f * std::abs(u(random));
        s.addSphere(scale * c + offset, scale * r, m);
        glm::vec3 corner(u(random), u(random), u(random));
        glm::vec3 edgeU(u(random), 0.3f, 0.1f);
        glm::vec3 edgeV(0.1f, u(random), 0.4f);
        s.addQuad(scale * corner + offset, scale * edgeU, scale * edgeV, m);
    }
    s.addPlane(scale * glm::vec3(0.0f, -1.5f, 0.0f) + offset, glm::vec3(0.1f, 1.0f, 0.0f), m);
    s.addPointLight(scale * glm::vec3(0.0f, 3.0f, 0.0f) + offset, glm::vec3(1.0f));
    s.finalize();
    return s;
}

TEST(Bvh, TraversalEqualsBruteForceOnRandomSoups) {
    for (std::size_t n : {0u, 1u, 3u, 50u, 2000u, 40000u}) {
        SCOPED_TRACE(std::to_string(n) + " triangles");
        Scene s = randomSoup(n, std::uint32_t(n) + 1);
        EXPECT_EQ(compareWithBruteForce(s, n > 10000 ? 2000 : 20000, 7), 0);
    }
}

// The quantized boxes where float steps are coarse or fine: large coordinates, tiny triangles, and
// small triangles far from the origin (not so small there that the intersection test itself
// loses them: a triangle a few float steps wide seen from afar is hit by rays that miss it).
TEST(Bvh, TraversalEqualsBruteForceAtLargeAndSmallScales) {
    struct Case {
        float scale;
        glm::vec3 offset;
    };
    for (Case c : {Case{1e8f, glm::vec3(0.0f)}, Case{1e-6f, glm::vec3(0.0f)}, Case{1e-2f, glm::vec3(100.0f, -50.0f, 30.0f)},
                   Case{1.0f, glm::vec3(3e3f, -2e3f, 1e3f)}}) {
        SCOPED_TRACE("scale " + std::to_string(c.scale) + ", offset x " + std::to_string(c.offset.x));
        Scene s = randomSoup(3000, 11, c.scale, c.offset);
        EXPECT_EQ(s.droppedTriangles, 0u);
        EXPECT_EQ(compareWithBruteForce(s, 4000, 5), 0);
    }
}

TEST(Bvh, TraversalEqualsBruteForceOnEveryShippedScene) {
    for (const std::string& path : test::shippedScenes({".json", ".glb", ".gltf"})) {
        SCOPED_TRACE(path);
        Scene s = loadSceneFile(path);
        EXPECT_EQ(compareWithBruteForce(s, 20000, 3), 0);
    }
}

// Every primitive in exactly one leaf, inside every box on its way from the root.
void expectEveryPrimitiveOnceInsideItsBoxes(const Scene& s) {
    ASSERT_FALSE(s.bvhNodes.empty());
    std::vector<int> seen(s.spheres.size() + s.quads.size() + s.triangles.size(), 0);
    auto slot = [&](std::uint32_t ref) {
        std::uint32_t kind = primitiveKind(ref);
        std::uint32_t index = primitiveIndex(ref);
        return kind == PRIM_SPHERE ? index : kind == PRIM_QUAD ? s.spheres.size() + index : s.spheres.size() + s.quads.size() + index;
    };
    auto inside = [&](std::uint32_t ref, glm::vec3 lo, glm::vec3 hi) {
        std::uint32_t kind = primitiveKind(ref);
        std::uint32_t i = primitiveIndex(ref);
        std::vector<glm::vec3> points;
        if (kind == PRIM_SPHERE) {
            points = {s.spheres[i].center - glm::vec3(s.spheres[i].radius), s.spheres[i].center + glm::vec3(s.spheres[i].radius)};
        } else if (kind == PRIM_QUAD) {
            const Quad& q = s.quads[i];
            points = {q.corner, q.corner + q.edgeU, q.corner + q.edgeV, q.corner + q.edgeU + q.edgeV};
        } else {
            points = {s.triangles[i].v0, s.triangles[i].v1, s.triangles[i].v2};
        }
        for (glm::vec3 p : points) {
            if (glm::any(glm::lessThan(p, lo)) || glm::any(glm::greaterThan(p, hi))) {
                return false;
            }
        }
        return true;
    };
    std::vector<std::uint32_t> stack{0};
    std::size_t outside = 0;
    std::size_t gaps = 0;  // a child after an empty slot
    while (!stack.empty()) {
        const WideBvhNode& n = s.bvhNodes[stack.back()];
        stack.pop_back();
        glm::vec3 scale = wideScale(n.scales);
        bool empty = false;
        for (std::uint32_t c = 0; c < BVH_WIDTH; ++c) {
            std::uint32_t kind = (n.kinds >> (8 * c)) & 0xffu;
            if (kind == WIDE_CHILD_EMPTY) {
                empty = true;
                continue;
            }
            gaps += empty ? 1 : 0;
            glm::vec3 q0(float((n.lowerX >> (8 * c)) & 0xffu), float((n.lowerY >> (8 * c)) & 0xffu), float((n.lowerZ >> (8 * c)) & 0xffu));
            glm::vec3 q1(float((n.upperX >> (8 * c)) & 0xffu), float((n.upperY >> (8 * c)) & 0xffu), float((n.upperZ >> (8 * c)) & 0xffu));
            glm::vec3 lo = n.origin + q0 * scale;
            glm::vec3 hi = n.origin + q1 * scale;
            if (kind == WIDE_CHILD_INNER) {
                ASSERT_LT(n.children[c], s.bvhNodes.size());
                stack.push_back(n.children[c]);
                continue;
            }
            ASSERT_LE(kind, BVH_LEAF_MAX);
            for (std::uint32_t k = n.children[c]; k < n.children[c] + kind; ++k) {
                seen[slot(s.primitiveRefs[k])] += 1;
                outside += inside(s.primitiveRefs[k], lo, hi) ? 0 : 1;
            }
        }
    }
    EXPECT_EQ(gaps, 0u);
    EXPECT_EQ(outside, 0u);
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(seen.size()));
    EXPECT_LE(s.bvh.stack, BVH_STACK_SIZE);
    EXPECT_EQ(s.bvh.wideNodes, s.bvhNodes.size());
    // Four children a node where there are enough (a binary node whose children are both leaves
    // opens no further: about half as many nodes).
    EXPECT_LT(s.bvh.wideNodes, s.bvh.nodes * 2 / 3);
    std::printf("bvh: %u primitives, %u binary nodes, %u leaves, depth %u, SAH cost %.1f; %u wide nodes, depth %u, stack "
                "%u, SAH cost %.1f\n",
                s.bvh.primitives, s.bvh.nodes, s.bvh.leaves, s.bvh.depth, s.bvh.sahCost, s.bvh.wideNodes, s.bvh.wideDepth,
                s.bvh.stack, s.bvh.wideSahCost);
}

TEST(Bvh, EveryPrimitiveOnceInsideItsBoxes) {
    expectEveryPrimitiveOnceInsideItsBoxes(randomSoup(5000, 9));
    // Large and tiny, and boxes a few float steps wide.
    expectEveryPrimitiveOnceInsideItsBoxes(randomSoup(3000, 11, 1e8f));
    expectEveryPrimitiveOnceInsideItsBoxes(randomSoup(3000, 11, 1e-6f));
    expectEveryPrimitiveOnceInsideItsBoxes(randomSoup(3000, 11, 1e-3f, glm::vec3(100.0f, -50.0f, 30.0f)));
}

// The hierarchy depends on the scene alone: built on one thread (every chunk in order) and on all,
// and built again, its nodes and references are the same bytes. The scenes are large enough that
// the top levels split their nodes over many chunks and leave many subtrees: a random soup (no
// order in memory) and the bench's mesh in the Cornell box (made in order, with walls).
TEST(Bvh, SameBytesOnAnyThreadCount) {
    std::vector<Scene> scenes;
    scenes.push_back(randomSoup(300000, 5));
    scenes.push_back(tools::meshBenchScene(400000));
    for (const Scene& s : scenes) {
        SCOPED_TRACE(std::to_string(s.triangles.size()) + " triangles");
        setThreadLimit(1);
        std::vector<WideBvhNode> serialNodes;
        std::vector<std::uint32_t> serialRefs;
        BvhStats serial = buildBvh(s, serialNodes, serialRefs);
        setThreadLimit(0);
        std::printf("bvh: %u primitives on 1 and %u threads: %u nodes, SAH cost %.3f\n", serial.primitives,
                    workerThreads(), serial.nodes, serial.sahCost);
        ASSERT_GT(serial.nodes, 1000u);
        for (int repeat = 0; repeat < 3; ++repeat) {
            std::vector<WideBvhNode> nodes;
            std::vector<std::uint32_t> refs;
            BvhStats parallel = buildBvh(s, nodes, refs);
            ASSERT_EQ(nodes.size(), serialNodes.size());
            ASSERT_EQ(refs.size(), serialRefs.size());
            EXPECT_EQ(std::memcmp(nodes.data(), serialNodes.data(), nodes.size() * sizeof(WideBvhNode)), 0);
            EXPECT_EQ(std::memcmp(refs.data(), serialRefs.data(), refs.size() * sizeof(std::uint32_t)), 0);
            EXPECT_EQ(parallel.sahCost, serial.sahCost);
            EXPECT_EQ(parallel.depth, serial.depth);
            EXPECT_EQ(parallel.leaves, serial.leaves);
            EXPECT_EQ(parallel.wideSahCost, serial.wideSahCost);
            EXPECT_EQ(parallel.stack, serial.stack);
        }
        // And the scene's own hierarchy (built by finalize, on all threads) is the same.
        EXPECT_EQ(std::memcmp(s.bvhNodes.data(), serialNodes.data(), serialNodes.size() * sizeof(WideBvhNode)), 0);
    }
}

// A million triangles in one spot: the hierarchy falls back to median splits and stays within
// the traversal's stack.
TEST(Bvh, CoincidentPrimitivesStayShallow) {
    Scene s;
    std::uint32_t m = s.addMaterial("m", makeDiffuse(glm::vec3(0.5f)));
    Mesh mesh;
    mesh.positions = {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)};
    mesh.triangles.assign(200000, glm::uvec3(0, 1, 2));
    mesh.materials.assign(200000, m);
    s.addMesh(mesh, glm::mat4(1.0f));
    s.addPointLight(glm::vec3(0, 0, 3), glm::vec3(1.0f));
    s.finalize();
    EXPECT_LE(s.bvh.stack, BVH_STACK_SIZE);
    EXPECT_EQ(compareWithBruteForce(s, 50, 1), 0);
}

}  // namespace
}  // namespace photon
