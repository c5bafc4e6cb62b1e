#include "core/frame/backend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/frame/scene_settings.h"
#include "core/settings/setting_specs.h"
#include "shared/map_photon.h"
#include "core/system/error.h"

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

void Backend::setScene(Scene scene) {
    scene_ = std::move(scene);
    camera_ = scene_.camera;
    sceneDirty_ = true;
    footprintsDirty_ = true;
    allocationDirty_ = true;
    frameIndex_ = 0;
    accumulated_ = 0;
}

void Backend::setSettings(const RenderSettings& settings) {
    settings_ = settings;
    std::fill(std::begin(grownCapacity_), std::end(grownCapacity_), 0u);
    allocationDirty_ = true;
    footprintsDirty_ = true;
    frameIndex_ = 0;
    accumulated_ = 0;
}

void Backend::setCamera(const CameraDesc& camera) {
    camera_ = camera;
    accumulated_ = 0;
    footprintsDirty_ = true;
}

void Backend::moveCamera(const CameraDesc& camera) {
    if (!settings_.reproject || accumulated_ == 0) {
        setCamera(camera);
        return;
    }
    if (!reprojecting_) {
        previousCamera_ = camera_;
        reprojecting_ = true;
    }
    camera_ = camera;
}

void Backend::resetAccumulation() { accumulated_ = 0; }

void Backend::setPathSplit(const PathSplit& split) {
    if (split.ranks == 0 || split.rank >= split.ranks) {
        throw std::invalid_argument("path split: rank " + std::to_string(split.rank) + " of " + std::to_string(split.ranks));
    }
    split_ = split;
    accumulated_ = 0;
}

void Backend::prepare() {
    if (!sceneDirty_ && !allocationDirty_) {
        return;
    }
    if (scene_.lights.empty()) {
        throw InputError("the scene has no lights");
    }
    validateSettings(settings_);
    measureRadii();
    PhotonBudget budget = planPhotons(scene_, settings_);
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        budget.capacity[m] = std::max(budget.capacity[m], grownCapacity_[m]);
    }
    BufferPlan plan = planBuffers(scene_, budget, settings_.width, settings_.height);
    adjustPlan(plan, budget);
    checkMemory(plan, memoryLimits(), settings_.width, settings_.height);
    std::uint64_t hostImage = std::uint64_t(settings_.width) * settings_.height * kHostBytesPerPixel;
    if (!buffersInHostMemory() && hostImage > availableHostMemory()) {
        throw InputError("the image needs " + formatMiB(hostImage) + " of host memory at " + std::to_string(settings_.width) +
                         "x" + std::to_string(settings_.height) + ", more than this machine has available; " +
                         whatToLower(BUFFER_PER_PIXEL));
    }
    if (sceneDirty_) {
        uploadScene(scene_, plan);
        sceneDirty_ = false;
    }
    bool same = std::equal(std::begin(budget.cells), std::end(budget.cells), std::begin(allocatedBudget_.cells)) &&
                allocatedWidth_ == settings_.width && allocatedHeight_ == settings_.height &&
                plan.scratchBytes == plan_.scratchBytes;
    for (const BufferInfo& info : kBuffers) {
        same = same && (info.size == BUFFER_PER_SCENE || plan.elements[info.binding] == plan_.elements[info.binding]);
    }
    if (!same) {
        allocate(plan, budget, settings_.width, settings_.height);
        allocatedBudget_ = budget;
        allocatedWidth_ = settings_.width;
        allocatedHeight_ = settings_.height;
    }
    plan_ = plan;
    budget_ = budget;
    allocationDirty_ = false;
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

FrameResult Backend::runFrame(const FrameParams& params, bool denoiseOnly) {
    beginStages(params);
    for (const StageInfo& stage : kStages) {
        bool denoise = stage.id == STAGE_DENOISE;
        bool optional = denoise || stage.id == STAGE_REPROJECT;
        std::uint32_t flag = denoise ? FLAG_DENOISE : FLAG_REPROJECT;
        if (denoiseOnly ? denoise : !optional || (params.flags & flag) != 0u) {
            runStage(stage.id, params);
        } else {
            skipStage(stage.id);
        }
    }
    return endStages();
}

void Backend::denoiseImage() {
    if (accumulated_ == 0 || denoisedFrames_ == accumulated_ || !denoises(settings_)) {
        return;
    }
    FrameParams params = params_;
    params.flags |= FLAG_DENOISE;
    FrameResult result = runFrame(params, true);
    stats_.ms[STAGE_DENOISE] = result.ms[STAGE_DENOISE];
    denoisedFrames_ = accumulated_;
}

void Backend::measureRadii() {
    if (!footprintsDirty_) {
        return;
    }
    footprints_ = measureFootprints(scene_, camera_, settings_);
    FrameRadii radii = firstFrameRadii(scene_, settings_, footprints_, planPhotons(scene_, settings_));
    validateForScene(settings_, scene_, radii);
    policy_.start(radii);
    footprintsDirty_ = false;
}

const FrameParams& Backend::beginFrame() {
    prepare();
    measureRadii();
    if (accumulated_ == 0) {
        reprojecting_ = false;  // restarted since the camera moved: nothing to carry
    }
    params_ = makeFrameParams(scene_, camera_, settings_, budget_, frameIndex_, accumulated_,
                              policy_.frame(settings_, accumulated_), split_);
    if (reprojecting_) {
        params_.flags |= FLAG_REPROJECT;
        params_.previousCamera = makeCamera(previousCamera_, settings_.width, settings_.height);
    }
    if (!denoiseEachFrame_) {
        params_.flags &= ~FLAG_DENOISE;
    }
    return params_;
}

bool Backend::endFrame(const FrameResult& result, bool mayRepeat) {
    stats_ = FrameStats{};
    stats_.ms = result.ms;
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        stats_.stored[m] = result.counters[COUNTER_STORED + m];
        stats_.capacity[m] = params_.grids[m].photonCapacity;
    }
    stats_.environmentPaths = result.counters[COUNTER_ENVIRONMENT_PATHS];
    stats_.environmentHits = result.counters[COUNTER_ENVIRONMENT_HITS];
    stats_.emitted[MAP_GLOBAL] = params_.globalPaths;
    stats_.emitted[MAP_CAUSTIC] = params_.causticPaths;
    bool dropped = growPhotonMaps();
    if (dropped && accumulated_ == 0 && mayRepeat) {
        return false;
    }
    if (dropped && !warnedDropped_) {
        std::fprintf(stderr, "photon: a photon map overflowed; photons were dropped and it was grown\n");
        warnedDropped_ = true;
    }
    policy_.observe(settings_, result.counters);
    frameIndex_ += 1;
    accumulated_ += 1;
    reprojecting_ = false;
    denoisedFrames_ = (params_.flags & FLAG_DENOISE) != 0u ? accumulated_ : 0u;
    return true;
}

bool Backend::growPhotonMaps() {
    bool dropped = false;
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        std::uint32_t stored = stats_.stored[m];
        std::uint32_t capacity = stats_.capacity[m];
        if (double(stored) <= 0.8 * double(capacity)) {
            continue;
        }
        dropped = dropped || stored > capacity;
        grownCapacity_[m] = static_cast<std::uint32_t>(std::min(double(kMapCapacityMax), std::ceil(double(stored) * 1.5)));
        allocationDirty_ = true;
    }
    return dropped;
}

Image Backend::image() {
    if (accumulated_ == 0) {
        return Image(settings_.width, settings_.height);
    }
    if (!denoises(settings_)) {
        return readImage(BINDING_ACCUMULATION);
    }
    denoiseImage();
    return readImage(BINDING_DENOISED);
}

Image Backend::rawImage() {
    if (accumulated_ == 0) {
        return Image(settings_.width, settings_.height);
    }
    return readImage(BINDING_ACCUMULATION);
}

Image Backend::readFrame() { return readImage(BINDING_FRAME); }

Image Backend::readImage(std::uint32_t binding) {
    Image image(allocatedWidth_, allocatedHeight_);
    if (!image.pixels.empty()) {
        readBuffer(binding, 0, image.pixels.size() * sizeof(glm::vec4), image.pixels.data());
    }
    return image;
}

template <typename T>
std::vector<T> Backend::readPerPixel(std::uint32_t binding) {
    std::vector<T> elements(std::size_t(allocatedWidth_) * allocatedHeight_);
    if (!elements.empty()) {
        readBuffer(binding, 0, elements.size() * sizeof(T), elements.data());
    }
    return elements;
}

std::vector<HitPoint> Backend::readHitPoints() { return readPerPixel<HitPoint>(BINDING_HIT_POINTS); }

std::vector<SppmPixel> Backend::readSppmPixels() { return readPerPixel<SppmPixel>(BINDING_SPPM_PIXELS); }

std::vector<PixelAov> Backend::readAovs() {
    if (!keepsAovs(settings_) || accumulated_ == 0) {
        return {};
    }
    return readPerPixel<PixelAov>(BINDING_AOVS);
}

PhotonMaps Backend::readPhotonMaps() {
    PhotonMaps maps;
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        const GridParams& grid = params_.grids[m];
        std::uint32_t stored = std::min(stats_.stored[m], grid.photonCapacity);
        maps.stored[m].resize(stored);
        if (stored > 0) {
            readBuffer(BINDING_SORTED_PHOTONS, std::uint64_t(grid.photonOffset) * sizeof(MapPhoton),
                       std::uint64_t(stored) * sizeof(MapPhoton), maps.stored[m].data());
        }
        maps.photons[m].reserve(stored);
        for (const MapPhoton& p : maps.stored[m]) {
            maps.photons[m].push_back(decodeMapPhoton(p, grid));
        }
        maps.cellStart[m].resize(std::size_t(grid.cellCount) + 1);
        readBuffer(BINDING_CELL_START, std::uint64_t(grid.cellOffset) * sizeof(std::uint32_t),
                   maps.cellStart[m].size() * sizeof(std::uint32_t), maps.cellStart[m].data());
    }
    return maps;
}

}  // namespace photon
