#include "core/frame/photon_use.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/frame/median.h"
#include "shared/estimate.h"

namespace photon {
namespace {

struct Disc {
    glm::vec3 centre;
    glm::vec3 normal;  // geometric, facing the eye: photons must come from this side
    float radius;
};

// Cells of a uniform grid, packed 21 bits an axis.
std::int64_t packCell(glm::ivec3 c) {
    auto axis = [](int v) { return std::int64_t(std::clamp(v, -(1 << 20), (1 << 20) - 1) + (1 << 20)); };
    return (axis(c.x) << 42) | (axis(c.y) << 21) | axis(c.z);
}

glm::ivec3 cellAt(glm::vec3 p, float cell) { return glm::ivec3(glm::floor(p / cell)); }

bool holds(const Disc& d, const Photon& p) {
    glm::vec3 offset = p.position - d.centre;
    return glm::dot(offset, offset) < d.radius * d.radius &&
           std::abs(glm::dot(offset, d.normal)) <= DISC_THICKNESS * d.radius &&
           glm::dot(octDecodeUnnormalized(p.incoming), d.normal) > 0.0f;
}

// The photons of `photons` that some disc holds. Each disc is listed in the cells its bounding
// box (discExtent: a thin slab for a wall) overlaps, cells of twice the median radius (or a quarter of the widest, so that no disc
// spans more than 9 cells an axis); a photon then looks in its own cell only.
std::uint64_t countGathered(const std::vector<Photon>& photons, const std::vector<Disc>& discs) {
    if (photons.empty() || discs.empty()) {
        return 0;
    }
    std::vector<double> radii;
    float widest = 0.0f;
    for (const Disc& d : discs) {
        radii.push_back(d.radius);
        widest = std::max(widest, d.radius);
    }
    float cell = std::max(2.0f * float(median(radii)), 0.25f * widest);
    std::vector<std::pair<std::int64_t, std::uint32_t>> entries;
    for (std::uint32_t i = 0; i < discs.size(); ++i) {
        glm::vec3 reach = discExtent(discs[i].normal, discs[i].radius, DISC_THICKNESS * discs[i].radius);
        glm::ivec3 lo = cellAt(discs[i].centre - reach, cell);
        glm::ivec3 hi = cellAt(discs[i].centre + reach, cell);
        for (int z = lo.z; z <= hi.z; ++z) {
            for (int y = lo.y; y <= hi.y; ++y) {
                for (int x = lo.x; x <= hi.x; ++x) {
                    entries.emplace_back(packCell({x, y, z}), i);
                }
            }
        }
    }
    std::sort(entries.begin(), entries.end());
    std::uint64_t gathered = 0;
    for (const Photon& p : photons) {
        std::int64_t key = packCell(cellAt(p.position, cell));
        auto it = std::lower_bound(entries.begin(), entries.end(), std::make_pair(key, 0u));
        for (; it != entries.end() && it->first == key; ++it) {
            if (holds(discs[it->second], p)) {
                gathered += 1;
                break;
            }
        }
    }
    return gathered;
}

// The cell estimate's photons: those of a cell that holds a visible point (estimateCell).
std::uint64_t countInCells(const std::vector<Photon>& photons, const std::vector<HitPoint>& hitPoints,
                           const GridParams& grid) {
    std::vector<std::int64_t> cells;
    for (const HitPoint& hp : hitPoints) {
        if (hp.material != NONE) {
            cells.push_back(packCell(cellOf(hp.position, grid)));
        }
    }
    std::sort(cells.begin(), cells.end());
    std::uint64_t gathered = 0;
    for (const Photon& p : photons) {
        gathered += std::binary_search(cells.begin(), cells.end(), packCell(cellOf(p.position, grid))) ? 1 : 0;
    }
    return gathered;
}

}  // namespace

PhotonUse measurePhotonUse(Renderer& backend) {
    PhotonUse use;
    PhotonMaps maps = backend.readPhotonMaps();
    std::vector<HitPoint> hitPoints = backend.readHitPoints();
    const FrameParams& params = backend.lastFrameParams();
    std::vector<SppmPixel> sppm;
    if (params.estimator == ESTIMATOR_SPPM) {
        sppm = backend.readSppmPixels();
    }
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        const GridParams& grid = params.grids[m];
        use.stored[m] = maps.photons[m].size();
        if (params.estimator == ESTIMATOR_CELL) {
            use.discs[m] = std::count_if(hitPoints.begin(), hitPoints.end(), [](const HitPoint& hp) { return hp.material != NONE; });
            use.gathered[m] = countInCells(maps.photons[m], hitPoints, grid);
            continue;
        }
        std::vector<Disc> discs;
        for (std::size_t p = 0; p < hitPoints.size(); ++p) {
            const HitPoint& hp = hitPoints[p];
            if (hp.material == NONE) {
                continue;
            }
            float r = params.estimator == ESTIMATOR_SPPM ? sppm[p].maps[m].radius : grid.radius;
            if (r > 0.0f && std::isfinite(r)) {
                discs.push_back({hp.position, octDecode(hp.geometricNormal), r});
            }
        }
        use.discs[m] = discs.size();
        use.gathered[m] = countGathered(maps.photons[m], discs);
    }
    return use;
}

}  // namespace photon
