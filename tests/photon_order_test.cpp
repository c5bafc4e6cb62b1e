// The deterministic grid build (shared/photon_map.h): whatever order the scatter's atomics hand out
// places in, every cell ends up holding its photons by id, across chunk boundaries too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

#include "shared/bindings.h"
#include "shared/photon_map.h"

namespace photon {
namespace {

constexpr std::uint32_t kCells = 64;

// Photons of one map whose cells are given outright: a cell of several chunks, cells at and just
// past a chunk's size, and small cells, with ids unique but unrelated to the stored order.
struct OrderFixture {
    std::vector<std::uint32_t> cellOf;
    std::vector<Photon> photons;
    std::vector<std::uint32_t> keys, counts, starts;
    std::vector<MapPhoton> sorted;
    std::vector<std::uint32_t> order;
    Bindings b{};

    OrderFixture() {
        std::mt19937 rng(7);
        auto add = [&](std::uint32_t cell, std::uint32_t n) { cellOf.insert(cellOf.end(), n, cell); };
        add(5, 3 * ORDER_CHUNK - 72);
        add(9, ORDER_CHUNK);
        add(10, ORDER_CHUNK + 1);
        add(20, 3000);  // a caustic focus: a dozen chunks
        for (std::uint32_t i = 0; i < 2000; ++i) {
            add(rng() % kCells, 1 + rng() % 12);
        }
        std::shuffle(cellOf.begin(), cellOf.end(), rng);
        std::uint32_t n = static_cast<std::uint32_t>(cellOf.size());
        std::vector<std::uint32_t> ids(n);
        std::iota(ids.begin(), ids.end(), 0u);
        std::shuffle(ids.begin(), ids.end(), rng);
        photons.resize(n);
        for (std::uint32_t i = 0; i < n; ++i) {
            photons[i].position = glm::vec3(0.001f * float(i), 0.5f, -0.25f);
            photons[i].power = glm::vec3(1.0f + float(i % 17));
            photons[i].id = ids[i] * 64u + (i % 64u);  // a path and a bounce
        }
        b.params.grids[MAP_GLOBAL].origin = glm::vec3(0.0f);
        b.params.grids[MAP_GLOBAL].cellSize = 1.0f;
        b.params.grids[MAP_GLOBAL].kind = GRID_HASHED;
        b.params.grids[MAP_GLOBAL].cellCount = kCells;
        b.params.grids[MAP_GLOBAL].photonCapacity = n;
        for (std::uint32_t m = MAP_GLOBAL + 1u; m < MAP_COUNT; ++m) {  // the other maps: empty, after it
            b.params.grids[m].photonOffset = n;
            b.params.grids[m].cellOffset = kCells + 1;
        }
        b.params.frameIndex = 3;
        b.params.seed = 11;
    }

    // The count and scan done directly, then the scatter in `scatterOrder` and the other steps.
    std::vector<MapPhoton> build(const std::vector<std::uint32_t>& scatterOrder) {
        std::uint32_t n = static_cast<std::uint32_t>(photons.size());
        keys = cellOf;
        counts.assign(kCells + 1, 0u);
        for (std::uint32_t c : cellOf) {
            counts[c] += 1;
        }
        starts.assign(kCells + 1, 0u);
        std::exclusive_scan(counts.begin(), counts.end(), starts.begin(), 0u);
        sorted.assign(n, MapPhoton{});
        order.assign(ORDER_ARRAYS * std::size_t(n), 0xdeadbeefu);  // stale pairs from an earlier frame
        b.photons = photons.data();
        b.photonKeys = keys.data();
        b.cellCounts = counts.data();
        b.cellStart = starts.data();
        b.sortedPhotons = sorted.data();
        b.photonOrder = order.data();
        for (std::uint32_t i : scatterOrder) {
            scatterPhotonId(b, MAP_GLOBAL, i);
        }
        for (std::uint32_t place = 0; place < n; ++place) {
            rankInChunk(b, MAP_GLOBAL, place);
        }
        for (std::uint32_t place = 0; place < n; ++place) {
            mergeChunks(b, MAP_GLOBAL, place);
        }
        return sorted;
    }

    // Each cell's photons by id, as the maps keep them.
    std::vector<MapPhoton> canonical() const {
        std::vector<std::uint32_t> byCellAndId(photons.size());
        std::iota(byCellAndId.begin(), byCellAndId.end(), 0u);
        std::sort(byCellAndId.begin(), byCellAndId.end(), [&](std::uint32_t x, std::uint32_t y) {
            return cellOf[x] != cellOf[y] ? cellOf[x] < cellOf[y] : photons[x].id < photons[y].id;
        });
        std::vector<MapPhoton> expected;
        for (std::uint32_t i : byCellAndId) {
            expected.push_back(encodeMapPhoton(photons[i], b.params.grids[MAP_GLOBAL], b.params.frameIndex, b.params.seed));
        }
        return expected;
    }
};

std::size_t misplaced(const std::vector<MapPhoton>& actual, const std::vector<MapPhoton>& expected) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
        n += std::memcmp(&actual[i], &expected[i], sizeof(MapPhoton)) != 0 ? 1 : 0;
    }
    return n;
}

TEST(PhotonOrder, EveryCellInIdOrderWhateverTheScatterOrder) {
    OrderFixture f;
    std::vector<MapPhoton> expected = f.canonical();
    std::vector<std::uint32_t> scatterOrder(f.photons.size());
    std::iota(scatterOrder.begin(), scatterOrder.end(), 0u);
    std::mt19937 rng(3);
    for (int trial = 0; trial < 3; ++trial) {
        SCOPED_TRACE("scatter order " + std::to_string(trial));
        std::vector<MapPhoton> actual = f.build(scatterOrder);
        EXPECT_EQ(misplaced(actual, expected), 0u) << "photons not in canonical order";
        EXPECT_TRUE(std::all_of(f.counts.begin(), f.counts.end(), [](std::uint32_t c) { return c == 0u; }))
            << "the scatter leaves the cell counts at zero";
        std::shuffle(scatterOrder.begin(), scatterOrder.end(), rng);
    }
}

}  // namespace
}  // namespace photon
