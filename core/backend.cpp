#include "backend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "error.h"

namespace photon {

GridStats gridStats(const std::vector<std::uint32_t>& cellStart) {
    GridStats s;
    if (cellStart.size() < 2) {
        return s;
    }
    s.cells = static_cast<std::uint32_t>(cellStart.size() - 1);
    std::uint64_t photons = 0;
    for (std::size_t c = 0; c + 1 < cellStart.size(); ++c) {
        std::uint32_t n = cellStart[c + 1] - cellStart[c];
        if (n > 0) {
            s.occupied += 1;
            photons += n;
            s.maxPerCell = std::max(s.maxPerCell, n);
        }
    }
    s.meanPerOccupied = s.occupied ? double(photons) / double(s.occupied) : 0.0;
    return s;
}

void Backend::setScene(const Scene& scene) {
    scene_ = scene;
    camera_ = scene.camera;
    sceneDirty_ = true;
    allocationDirty_ = true;
    frameIndex_ = 0;
    accumulated_ = 0;
}

void Backend::setSettings(const RenderSettings& settings) {
    settings_ = settings;
    std::fill(std::begin(grownCapacity_), std::end(grownCapacity_), 0u);
    allocationDirty_ = true;
    frameIndex_ = 0;
    accumulated_ = 0;
}

void Backend::setCamera(const CameraDesc& camera) {
    camera_ = camera;
    accumulated_ = 0;
}

void Backend::resetAccumulation() { accumulated_ = 0; }

void Backend::prepare() {
    if (settings_.width == 0 || settings_.height == 0) {
        throw InputError("image size must be at least 1×1");
    }
    if (scene_.lights.empty()) {
        throw InputError("the scene has no lights");
    }
    if (sceneDirty_) {
        uploadScene(scene_);
        sceneDirty_ = false;
    }
    if (allocationDirty_) {
        PhotonBudget budget = planPhotons(scene_, settings_);
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            budget.capacity[m] = std::max(budget.capacity[m], grownCapacity_[m]);
        }
        bool same = allocatedWidth_ == settings_.width && allocatedHeight_ == settings_.height &&
                    budget.globalPaths == allocatedBudget_.globalPaths &&
                    budget.causticPaths == allocatedBudget_.causticPaths &&
                    std::equal(std::begin(budget.capacity), std::end(budget.capacity), std::begin(allocatedBudget_.capacity)) &&
                    std::equal(std::begin(budget.cells), std::end(budget.cells), std::begin(allocatedBudget_.cells));
        if (!same) {
            allocate(budget, settings_.width, settings_.height);
            allocatedBudget_ = budget;
            allocatedWidth_ = settings_.width;
            allocatedHeight_ = settings_.height;
        }
        budget_ = budget;
        allocationDirty_ = false;
    }
}

void Backend::renderFrame() {
    // A first frame that lost photons runs again with room for them: it replaces the
    // accumulation, so nothing of the short frame remains. Later frames keep what they have.
    for (bool first = true;; first = false) {
        const FrameParams& params = beginFrame();
        if (endFrame(runFrame(params), first)) {
            break;
        }
    }
}

const FrameParams& Backend::beginFrame() {
    prepare();
    params_ = makeFrameParams(scene_, camera_, settings_, budget_, frameIndex_, accumulated_);
    return params_;
}

bool Backend::endFrame(const FrameStats& stats, bool mayRepeat) {
    stats_ = stats;
    bool dropped = growPhotonMaps();
    if (dropped && accumulated_ == 0 && mayRepeat) {
        return false;
    }
    if (dropped && !warnedDropped_) {
        std::fprintf(stderr, "photon: a photon map overflowed; photons were dropped and it was grown\n");
        warnedDropped_ = true;
    }
    frameIndex_ += 1;
    accumulated_ += 1;
    return true;
}

bool Backend::growPhotonMaps() {
    bool dropped = false;
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        std::uint32_t stored = stats_.stored[m];
        std::uint32_t capacity = stats_.capacity[m];
        if (capacity == NONE || double(stored) <= 0.8 * double(capacity)) {
            continue;
        }
        dropped = dropped || stored > capacity;
        grownCapacity_[m] = static_cast<std::uint32_t>(std::min(4.0e9, std::ceil(double(stored) * 1.5)));
        allocationDirty_ = true;
    }
    return dropped;
}

Image Backend::image() {
    if (accumulated_ == 0) {
        return Image(settings_.width, settings_.height);
    }
    return readAccumulation();
}

}  // namespace photon
