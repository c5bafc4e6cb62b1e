#include "backend.h"

#include <algorithm>

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
    prepare();
    params_ = makeFrameParams(scene_, camera_, settings_, budget_, frameIndex_, accumulated_);
    stats_ = runFrame(params_);
    frameIndex_ += 1;
    accumulated_ += 1;
}

Image Backend::image() {
    if (accumulated_ == 0) {
        return Image(settings_.width, settings_.height);
    }
    return readAccumulation();
}

}  // namespace photon
