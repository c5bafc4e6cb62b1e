// Intersection edge cases, Fresnel, octahedral vectors, grid cells and hashing, kernels.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "shared/bsdf.h"
#include "shared/estimate.h"
#include "shared/grid.h"
#include "shared/intersect.h"
#include "shared/progressive.h"
#include "test_util.h"

namespace photon {
namespace {

Ray ray(vec3 o, vec3 d) { return makeRay(o, glm::normalize(d), FLOAT_MAX); }

TEST(Intersect, SphereFromOutsideInsideAndBehind) {
    EXPECT_FLOAT_EQ(intersectSphere(ray(vec3(0, 0, -5), vec3(0, 0, 1)), vec3(0), 1.0f, FLOAT_MAX), 4.0f);
    EXPECT_FLOAT_EQ(intersectSphere(ray(vec3(0), vec3(0, 0, 1)), vec3(0), 1.0f, FLOAT_MAX), 1.0f);  // inside
    EXPECT_EQ(intersectSphere(ray(vec3(0, 0, 5), vec3(0, 0, 1)), vec3(0), 1.0f, FLOAT_MAX), FLOAT_MAX);  // behind
    EXPECT_EQ(intersectSphere(ray(vec3(0, 2, -5), vec3(0, 0, 1)), vec3(0), 1.0f, FLOAT_MAX), FLOAT_MAX);  // miss
    EXPECT_EQ(intersectSphere(ray(vec3(0, 0, -5), vec3(0, 0, 1)), vec3(0), 1.0f, 3.0f), 3.0f);  // beyond tMax
}

TEST(Intersect, SphereFarAwayIsStillPrecise) {
    // A unit sphere 10⁴ away: the naive b² - c formula loses every digit of the discriminant.
    float t = intersectSphere(ray(vec3(0, 0.5f, -1.0e4f), vec3(0, 0, 1)), vec3(0), 1.0f, FLOAT_MAX);
    EXPECT_NEAR(t, 1.0e4f - std::sqrt(0.75f), 2e-3f);
}

TEST(Intersect, PlaneParallelAndFacing) {
    EXPECT_EQ(intersectPlane(ray(vec3(0, 1, 0), vec3(1, 0, 0)), vec3(0, 1, 0), 0.0f, FLOAT_MAX), FLOAT_MAX);
    EXPECT_FLOAT_EQ(intersectPlane(ray(vec3(0, 1, 0), vec3(0, -1, 0)), vec3(0, 1, 0), 0.0f, FLOAT_MAX), 1.0f);
    EXPECT_FLOAT_EQ(intersectPlane(ray(vec3(0, -1, 0), vec3(0, 1, 0)), vec3(0, 1, 0), 0.0f, FLOAT_MAX), 1.0f);  // back side
}

TEST(Intersect, QuadInsideOutsideAndEdges) {
    Scene s;
    s.addQuad(vec3(0), vec3(2, 0, 0), vec3(0, 0, 1), 0);
    const Quad& q = s.quads[0];
    EXPECT_FLOAT_EQ(intersectQuad(ray(vec3(1, 1, 0.5f), vec3(0, -1, 0)), q, FLOAT_MAX), 1.0f);
    EXPECT_FLOAT_EQ(intersectQuad(ray(vec3(1, -1, 0.5f), vec3(0, 1, 0)), q, FLOAT_MAX), 1.0f);  // two-sided
    EXPECT_EQ(intersectQuad(ray(vec3(2.01f, 1, 0.5f), vec3(0, -1, 0)), q, FLOAT_MAX), FLOAT_MAX);
    EXPECT_EQ(intersectQuad(ray(vec3(1, 1, -0.01f), vec3(0, -1, 0)), q, FLOAT_MAX), FLOAT_MAX);
    EXPECT_FLOAT_EQ(intersectQuad(ray(vec3(2, 1, 1), vec3(0, -1, 0)), q, FLOAT_MAX), 1.0f);  // corner
    EXPECT_FLOAT_EQ(s.quads[0].area, 2.0f);
}

float hitTriangle(const Ray& r, const Triangle& t) {
    float b1;
    float b2;
    return intersectTriangle(makeRayFrame(r), t, FLOAT_MAX, b1, b2);
}

TEST(Intersect, TriangleEdgesAndDegenerate) {
    Triangle t{};
    t.v0 = vec3(0);
    t.v1 = vec3(1, 0, 0);
    t.v2 = vec3(0, 1, 0);
    EXPECT_FLOAT_EQ(hitTriangle(ray(vec3(0.25f, 0.25f, 1), vec3(0, 0, -1)), t), 1.0f);
    EXPECT_FLOAT_EQ(hitTriangle(ray(vec3(0.25f, 0.25f, -1), vec3(0, 0, 1)), t), 1.0f);  // two-sided
    EXPECT_EQ(hitTriangle(ray(vec3(0.6f, 0.6f, 1), vec3(0, 0, -1)), t), FLOAT_MAX);
    EXPECT_EQ(hitTriangle(ray(vec3(0.25f, 0.25f, 1), vec3(1, 0, 0)), t), FLOAT_MAX);  // parallel
    float b1;
    float b2;
    intersectTriangle(makeRayFrame(ray(vec3(0.25f, 0.5f, 1), vec3(0, 0, -1))), t, FLOAT_MAX, b1, b2);
    EXPECT_FLOAT_EQ(b1, 0.25f);  // the weights of v1 and v2
    EXPECT_FLOAT_EQ(b2, 0.5f);
    t.v2 = vec3(2, 0, 0);  // degenerate
    EXPECT_EQ(hitTriangle(ray(vec3(0.25f, 0.0f, 1), vec3(0, 0, -1)), t), FLOAT_MAX);
}

// Watertight: rays through the shared edge, and the shared vertex, of a fan of triangles hit one
// of them, never neither (Woop et al. 2013).
TEST(Intersect, TrianglesSharingAnEdgeLeaveNoGap) {
    Rng rng = rngCreate(3, 0, 0, 0);
    vec3 centre(0.3f, -0.2f, 0.1f);
    const int fan = 7;
    Triangle tris[fan];
    for (int i = 0; i < fan; ++i) {
        float a0 = 6.2831853f * float(i) / fan;
        float a1 = 6.2831853f * float(i + 1) / fan;
        tris[i].v0 = centre;
        tris[i].v1 = centre + vec3(std::cos(a0), std::sin(a0), 0.0f);
        tris[i].v2 = centre + vec3(std::cos(a1), std::sin(a1), 0.0f);
    }
    int gaps = 0;
    for (int k = 0; k < 20000; ++k) {
        // Towards a point on an edge or at the centre, from a random origin above or below.
        int edge = k % fan;
        float along = k % 10 == 0 ? 0.0f : rngNext(rng);
        float a = 6.2831853f * float(edge) / fan;
        vec3 target = centre + along * vec3(std::cos(a), std::sin(a), 0.0f);
        vec3 origin = target + vec3(rngNext(rng) - 0.5f, rngNext(rng) - 0.5f, k % 2 ? 1.0f : -1.0f) * 3.0f;
        Ray r = ray(origin, unitVector(target - origin));
        bool hit = false;
        for (const Triangle& t : tris) {
            hit = hit || hitTriangle(r, t) < FLOAT_MAX;
        }
        gaps += hit ? 0 : 1;
    }
    EXPECT_EQ(gaps, 0);
}

TEST(Intersect, ClosestHitAcrossPrimitiveKinds) {
    Scene s;
    std::uint32_t m = s.addMaterial("white", makeDiffuse(vec3(0.5f)));
    s.addSphere(vec3(0, 0, -3), 1.0f, m);
    s.addPlane(vec3(0, 0, -10), vec3(0, 0, 1), m);
    s.addQuad(vec3(-1, -1, -1.5f), vec3(2, 0, 0), vec3(0, 2, 0), m);
    s.addPointLight(vec3(0, 5, 0), vec3(1));
    test::SceneBindings sb(s);
    Hit hit;
    ASSERT_TRUE(traceClosest(sb.bindings, ray(vec3(0), vec3(0, 0, -1)), hit));
    EXPECT_EQ(hit.kind, PRIM_QUAD);
    EXPECT_FLOAT_EQ(hit.t, 1.5f);
    ASSERT_TRUE(traceClosest(sb.bindings, ray(vec3(0, 1.5f, 0), vec3(0, 0, -1)), hit));
    EXPECT_EQ(hit.kind, PRIM_PLANE);
    EXPECT_FALSE(traceOccluded(sb.bindings, vec3(0), vec3(0, 0, -1), 1.4f));
    EXPECT_TRUE(traceOccluded(sb.bindings, vec3(0), vec3(0, 0, -1), 1.6f));
}

#ifdef PH_WIDE_BOX_SIMD
// The CPU's SSE four-box test (wide_box_test_simd.h) answers as the portable child-by-child test,
// bit for bit, on random nodes: inverted boxes (missed), children absent after the first empty
// one, rays from inside boxes, rays along an axis (an inverse direction of 1e20), short tMax.
TEST(Intersect, WideBoxTestSimdMatchesTheChildByChildTest) {
    std::mt19937 rng(41u);
    std::uniform_real_distribution<float> coordinate(-8.0f, 8.0f);
    auto exponents = [&]() { return (120u + rng() % 8u) | ((120u + rng() % 8u) << 8u) | ((120u + rng() % 8u) << 16u); };
    // Planes of four children along one axis (lower and upper words, a byte per child); one box in
    // eight inverted, which is missed.
    auto planes = [&](std::uint32_t& lower, std::uint32_t& upper) {
        lower = 0u;
        upper = 0u;
        for (std::uint32_t i = 0u; i < BVH_WIDTH; ++i) {
            std::uint32_t a = rng() % 256u;
            std::uint32_t b = rng() % 256u;
            bool inverted = rng() % 8u == 0u;
            lower |= ((a < b) != inverted ? a : b) << (8u * i);
            upper |= ((a < b) != inverted ? b : a) << (8u * i);
        }
    };
    auto kinds = [&]() {
        const std::uint32_t choices[4] = {WIDE_CHILD_EMPTY, WIDE_CHILD_INNER, 1u, 4u};
        std::uint32_t k = 0u;
        for (std::uint32_t i = 0u; i < BVH_WIDTH; ++i) {
            k |= choices[rng() % 4u] << (8u * i);
        }
        return k;
    };
    int hits = 0;
    int mismatches = 0;
    for (int i = 0; i < 200000; ++i) {
        WideBvhNode n{};
        n.origin = vec3(coordinate(rng), coordinate(rng), coordinate(rng));
        n.scales = exponents();
        planes(n.lowerX, n.upperX);
        planes(n.lowerY, n.upperY);
        planes(n.lowerZ, n.upperZ);
        n.kinds = kinds();
        n.pad0 = rng();
        vec3 scale = wideScale(n.scales);
        vec3 origin(coordinate(rng), coordinate(rng), coordinate(rng));
        vec3 target(float(rng() % 256u), float(rng() % 256u), float(rng() % 256u));  // aimed into the node
        vec3 d = n.origin + target * scale - origin;
        if (rng() % 4u == 0u) {
            d[rng() % 3u] = 0.0f;  // parallel to an axis
        }
        float tMax = (rng() % 2u == 0u) ? FLOAT_MAX : std::abs(coordinate(rng));
        RayFrame f = makeRayFrame(makeRay(origin, glm::normalize(d), tMax));
        vec4 simd = wideChildEntriesSimd(n, f.origin, f.inverseDirection, scale, tMax);
        vec4 portable = vec4(FLOAT_MAX);  // traceRay's portable loop
        for (std::uint32_t c = 0u; c < BVH_WIDTH && ((n.kinds >> (8u * c)) & 0xffu) != WIDE_CHILD_EMPTY; ++c) {
            portable[c] = wideChildEntry(f, n, scale, c, tMax);
        }
        for (int c = 0; c < 4; ++c) {
            hits += portable[c] < FLOAT_MAX ? 1 : 0;
            mismatches += floatBitsToUint(simd[c]) != floatBitsToUint(portable[c]) ? 1 : 0;
        }
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(hits, 20000);  // enough boxes are met for the comparison to mean something
}
#endif

TEST(Fresnel, NormalIncidenceGrazingAndTotalInternalReflection) {
    float n = 1.5f;
    float r0 = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
    EXPECT_NEAR(fresnelDielectric(1.0f, n), r0, 1e-6f);
    EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f / n), r0, 1e-6f);
    EXPECT_NEAR(fresnelDielectric(1e-4f, n), 1.0f, 1e-3f);
    // Inside glass beyond the critical angle asin(1/1.5) = 41.8°.
    EXPECT_EQ(fresnelDielectric(std::cos(0.8f), 1.0f / n), 1.0f);
    // Brewster's angle: p-polarised reflection vanishes, so F = rs²/2.
    float cosB = std::cos(std::atan(n));
    float cosT = std::sqrt(1.0f - (1.0f - cosB * cosB) / (n * n));
    float rs = (cosB - n * cosT) / (cosB + n * cosT);
    EXPECT_NEAR(fresnelDielectric(cosB, n), 0.5f * rs * rs, 1e-6f);
}

TEST(Fresnel, RefractionObeysSnell) {
    vec3 n(0, 0, 1);
    vec3 wo = glm::normalize(vec3(1, 0, 1));  // 45°
    vec3 wt;
    ASSERT_TRUE(refractThrough(wo, n, 1.5f, wt));
    EXPECT_NEAR(glm::length(wt), 1.0f, 1e-6f);
    float sinI = std::sqrt(0.5f);
    float sinT = std::sqrt(wt.x * wt.x + wt.y * wt.y);
    EXPECT_NEAR(sinI, 1.5f * sinT, 1e-6f);
    EXPECT_LT(wt.z, 0.0f);
    EXPECT_FALSE(refractThrough(glm::normalize(vec3(1, 0, 0.2f)), n, 1.0f / 1.5f, wt));  // TIR
}

TEST(Octahedral, RoundTripWithinTenMicroradians) {
    Rng rng = rngCreate(1u, 1u, 1u, 1u);
    for (int i = 0; i < 100000; ++i) {
        float u1 = rngNext(rng);
        float u2 = rngNext(rng);
        vec3 d = sampleUniformSphere(u1, u2);
        vec3 e = octDecode(octEncode(d));
        EXPECT_LT(glm::length(d - e), 1e-4f);  // 1e-4 rad
    }
    for (vec3 axis : {vec3(1, 0, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1)}) {
        EXPECT_LT(glm::length(octDecode(octEncode(axis)) - axis), 1e-6f);
    }
}

GridParams hashedGrid(float cellSize) {
    GridParams g{};
    g.kind = GRID_HASHED;
    g.cellSize = cellSize;
    g.cellCount = 1u << 16;
    return g;
}

TEST(Grid, NegativeCoordinatesUseFloor) {
    GridParams g = hashedGrid(1.0f);
    EXPECT_EQ(cellOf(vec3(-0.5f, 0.5f, -1.0f), g), ivec3(-1, 0, -1));
    EXPECT_EQ(cellOf(vec3(-1.5f, -0.0f, 2.5f), g), ivec3(-2, 0, 2));
    // Cells on either side of zero are distinct, as are their hashes.
    EXPECT_NE(photonCellKey(vec3(-0.5f, 0, 0), g), photonCellKey(vec3(0.5f, 0, 0), g));
}

TEST(Grid, BoundedClampsOutsidePointsIntoBorderCells) {
    GridParams g{};
    g.kind = GRID_BOUNDED;
    g.origin = vec3(-1);
    g.cellSize = 0.5f;
    g.resolution = 4;
    g.cellCount = 64;
    EXPECT_EQ(cellOf(vec3(-5, 0, 7), g), ivec3(0, 2, 3));
    EXPECT_EQ(cellKey(ivec3(3, 3, 3), g), 63u);
    EXPECT_EQ(cellKey(ivec3(1, 2, 3), g), (3u * 4 + 2) * 4 + 1);
}

TEST(Grid, HashSpreadsNeighbouringCells) {
    // The 32³ cells around the origin should fill a 2^16 table without piling up.
    GridParams g = hashedGrid(1.0f);
    std::vector<int> load(g.cellCount, 0);
    for (int z = -16; z < 16; ++z) {
        for (int y = -16; y < 16; ++y) {
            for (int x = -16; x < 16; ++x) {
                load[cellKey(ivec3(x, y, z), g)] += 1;
            }
        }
    }
    EXPECT_LE(*std::max_element(load.begin(), load.end()), 8);
}

TEST(Grid, NeighbourhoodsNeverShareABucket) {
    // Any 3×3×3 block of cells, anywhere (negative coordinates too), has 27 distinct keys, even in
    // the smallest table: queries need no duplicate check.
    GridParams g = hashedGrid(1.0f);
    g.cellCount = 64;
    Rng rng = rngCreate(4u, 0u, 0u, 0u);
    for (int trial = 0; trial < 2000; ++trial) {
        ivec3 base(int(rngNextUint(rng) % 2000u) - 1000, int(rngNextUint(rng) % 2000u) - 1000,
                   int(rngNextUint(rng) % 2000u) - 1000);
        std::vector<std::uint32_t> keys;
        for (int z = 0; z < 3; ++z) {
            for (int y = 0; y < 3; ++y) {
                for (int x = 0; x < 3; ++x) {
                    keys.push_back(cellKey(base + ivec3(x, y, z), g));
                }
            }
        }
        std::sort(keys.begin(), keys.end());
        ASSERT_EQ(std::unique(keys.begin(), keys.end()), keys.end()) << base.x << " " << base.y << " " << base.z;
    }
}

TEST(CellQuery, CoversTheBallWithAtMostThreeCellsPerAxis) {
    GridParams g = hashedGrid(0.1f);  // cells of edge r for r = 0.1
    for (vec3 x : {vec3(0.05f, -0.02f, 0.31f), vec3(-0.1f, 0.0f, 0.1f), vec3(0.0f)}) {
        CellQuery q = beginCellQuery(x, vec3(0.1f), 0.1f, g);
        int cells = 0;
        std::uint32_t key;
        while (nextCell(q, g, key)) {
            cells += 1;
        }
        ivec3 span = cellOf(x + vec3(0.1f), g) - cellOf(x - vec3(0.1f), g) + ivec3(1);
        EXPECT_EQ(cells, span.x * span.y * span.z);
        EXPECT_LE(cells, 27);
    }
}

// A query wider than the cells (an sppm pixel's radius) visits every cell it overlaps, and keeps
// only the photons of the cell it visits: a photon is found once, however the buckets collide.
TEST(CellQuery, WiderQueriesAreFilteredToTheVisitedCell) {
    GridParams g = hashedGrid(0.1f);
    g.cellCount = 64;  // so small that distant cells share buckets
    vec3 x(0.03f, 0.04f, 0.05f);
    float r = 0.45f;
    CellQuery q = beginCellQuery(x, vec3(r), r, g);
    EXPECT_TRUE(q.filtered);
    vec3 photon(0.31f, -0.22f, 0.12f);
    Photon record{};
    record.position = photon;
    MapPhoton stored = encodeMapPhoton(record, g, 0u, 0u);
    ivec3 own = cellOf(photon, g);
    int found = 0;
    int cells = 0;
    std::uint32_t key;
    while (nextCell(q, g, key)) {
        cells += 1;
        if (key == photonCellKey(photon, g) && inVisitedCell(q, g, stored)) {
            found += 1;
            EXPECT_EQ(q.cell, own);
        }
    }
    EXPECT_EQ(cells, 10 * 10 * 10);
    EXPECT_EQ(found, 1);
}

TEST(CellQuery, DiscOfAnAxisAlignedWallIsOneCellThick) {
    GridParams g = hashedGrid(0.1f);
    vec3 e = discExtent(vec3(0, 0, 1), 0.1f, 0.025f);
    EXPECT_FLOAT_EQ(e.x, 0.1f);
    EXPECT_FLOAT_EQ(e.z, 0.025f);
    CellQuery q = beginCellQuery(vec3(0.05f, 0.05f, 0.05f), e, 0.1f, g);
    int cells = 0;
    std::uint32_t key;
    while (nextCell(q, g, key)) {
        cells += 1;
    }
    EXPECT_EQ(cells, 9);  // 3 × 3 × 1 instead of 27 for the ball
    // A tilted disc's box lies within the ball's.
    vec3 tilted = discExtent(glm::normalize(vec3(1, 1, 1)), 0.1f, 0.025f);
    EXPECT_LT(tilted.x, 0.1f);
}

TEST(Kernels, IntegrateToOneOverTheDisc) {
    for (std::uint32_t k : {KERNEL_BOX, KERNEL_CONE, KERNEL_EPANECHNIKOV}) {
        // ∫_0^r K(d) 2πd dd · norm / (πr²) with r = 1.
        double sum = 0.0;
        int n = 100000;
        for (int i = 0; i < n; ++i) {
            double d = (i + 0.5) / n;
            sum += kernelProfile(k, float(d * d)) * 2.0 * d / n;
        }
        EXPECT_NEAR(sum * kernelNorm(k), 1.0, 1e-4) << "kernel " << k;
    }
}

TEST(Progressive, RadiusFollowsKnausZwicker) {
    float r0 = 0.1f;
    float alpha = 2.0f / 3.0f;
    double r2 = r0 * r0;
    for (std::uint32_t i = 0; i < 50; ++i) {
        EXPECT_NEAR(progressiveRadius(r0, alpha, i), std::sqrt(r2), 1e-6);
        r2 *= (i + alpha) / (i + 1.0);
    }
    vec4 mean(0.0f);
    for (std::uint32_t n = 0; n < 4; ++n) {
        mean = accumulateMean(mean, vec4(float(n)), n);
    }
    EXPECT_FLOAT_EQ(mean.x, 1.5f);
}

}  // namespace
}  // namespace photon
