// The work split of a frame between several renderers (the multi-GPU path of issue 12): rank r of
// N traces the r-th index range of the frame's photon paths. Together the ranks must trace exactly
// the photons one renderer traces (same positions, directions and powers, bit for bit, in each
// map: the maps' power rounding draws from each photon's id, so the ids must match too).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "core/render/devices.h"
#include "core/loaders/scene_loader.h"
#include "test_util.h"

namespace photon {
namespace {

bool before(const MapPhoton& a, const MapPhoton& b) { return std::memcmp(&a, &b, sizeof(MapPhoton)) < 0; }

std::vector<MapPhoton> sortedByBytes(std::vector<MapPhoton> photons) {
    std::sort(photons.begin(), photons.end(), before);
    return photons;
}

bool samePhoton(const MapPhoton& a, const MapPhoton& b) { return std::memcmp(&a, &b, sizeof(MapPhoton)) == 0; }

TEST(PathSplit, RanksTogetherTraceThePhotonsOfOne) {
    for (const char* name : {"cornell.json", "bunny.json"}) {
        Scene scene = loadSceneFile(test::scenesDir() + "/" + name);
        RenderSettings s = scene.render;
        s.width = 32;
        s.height = 24;
        s.photons = 30001;  // not a multiple of the ranks
        s.frames = 1;
        auto backend = createRenderer("cpu");
        backend->setScene(scene);
        backend->setSettings(s);
        backend->renderFrame();
        PhotonMaps whole = backend->readPhotonMaps();
        for (std::uint32_t ranks : {2u, 3u}) {
            std::vector<MapPhoton> merged[MAP_COUNT];
            std::uint64_t paths = 0;
            for (std::uint32_t rank = 0; rank < ranks; ++rank) {
                // One renderer per rank, as one per GPU: each at frame 0, whose random numbers they share.
                auto share = createRenderer("cpu");
                share->setScene(scene);
                share->setSettings(s);
                share->setPathSplit({rank, ranks});
                share->renderFrame();
                paths += share->lastFrameParams().pathCount;
                PhotonMaps part = share->readPhotonMaps();
                for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
                    merged[m].insert(merged[m].end(), part.stored[m].begin(), part.stored[m].end());
                }
            }
            SCOPED_TRACE(std::string(name) + ", " + std::to_string(ranks) + " ranks");
            EXPECT_EQ(paths, s.photons);
            for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
                std::vector<MapPhoton> a = sortedByBytes(merged[m]);
                std::vector<MapPhoton> b = sortedByBytes(whole.stored[m]);
                ASSERT_EQ(a.size(), b.size()) << "map " << m;
                EXPECT_TRUE(b.size() > 0u || m == MAP_VOLUME) << "map " << m;  // these scenes have no media
                std::size_t differing = 0;
                for (std::size_t i = 0; i < a.size(); ++i) {
                    differing += samePhoton(a[i], b[i]) ? 0 : 1;
                }
                EXPECT_EQ(differing, 0u) << "map " << m;
            }
        }
    }
}

TEST(PathSplit, BadRanksAreRefused) {
    auto backend = createRenderer("cpu");
    EXPECT_THROW(backend->setPathSplit({2, 2}), std::invalid_argument);
    EXPECT_THROW(backend->setPathSplit({0, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace photon
