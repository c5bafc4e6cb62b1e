#include "core/frame/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

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

Renderer::Renderer(std::vector<std::unique_ptr<Device>> devices, std::unique_ptr<Collective> collective)
    : devices_(std::move(devices)), collective_(std::move(collective)) {
    if (devices_.empty() || !collective_) {
        throw std::invalid_argument("a renderer needs a device and a collective");
    }
    split_ = {collective_->process(), collective_->processes()};
}

Renderer::~Renderer() = default;

std::string Renderer::name() const {
    std::string names;
    for (const auto& d : devices_) {
        names += (names.empty() ? "" : ",") + d->name();
    }
    return names;
}

std::string Renderer::deviceName() const {
    std::string names;
    for (const auto& d : devices_) {
        names += (names.empty() ? "" : " + ") + d->deviceName();
    }
    return names;
}

bool Renderer::runsOnCpu() const {
    return std::all_of(devices_.begin(), devices_.end(), [](const auto& d) { return d->runsOnCpu(); });
}

void Renderer::setScene(Scene scene) {
    scene_ = std::move(scene);
    camera_ = scene_.camera;
    sceneDirty_ = true;
    restart();
}

void Renderer::setSettings(const RenderSettings& settings) {
    settings_ = settings;
    std::fill(std::begin(grownCapacity_), std::end(grownCapacity_), 0u);
    restart();
}

void Renderer::restart() {
    allocationDirty_ = true;
    footprintsDirty_ = true;
    frameIndex_ = 0;
    accumulated_ = 0;
}

void Renderer::setCamera(const CameraDesc& camera) {
    camera_ = camera;
    accumulated_ = 0;
    footprintsDirty_ = true;
}

void Renderer::moveCamera(const CameraDesc& camera) {
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

void Renderer::resetAccumulation() { accumulated_ = 0; }

void Renderer::setPathSplit(const PathSplit& split) {
    if (split.ranks == 0 || split.rank >= split.ranks) {
        throw std::invalid_argument("path split: rank " + std::to_string(split.rank) + " of " + std::to_string(split.ranks));
    }
    split_ = split;
    accumulated_ = 0;
}

void Renderer::prepare() {
    if (!sceneDirty_ && !allocationDirty_) {
        return;
    }
    if (scene_.lights.empty()) {
        throw InputError("the scene has no lights");
    }
    validateSettings(settings_);
    if (collective_->processes() > 1) {
        collective_->checkSameInputs(renderFingerprints(scene_, camera_, settings_));
    }
    measureRadii();
    PhotonBudget budget = planPhotons(scene_, settings_);
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        budget.capacity[m] = std::max(budget.capacity[m], grownCapacity_[m]);
    }
    std::vector<BufferPlan> plans;
    for (const auto& device : devices_) {
        BufferPlan plan = planBuffers(scene_, budget, settings_.width, settings_.height);
        if (device != devices_.front()) {
            keepPhotonPassBuffers(plan);
        }
        device->adjustPlan(plan, budget);
        checkMemory(plan, device->memoryLimits(), settings_.width, settings_.height);
        plans.push_back(plan);
    }
    // The images read back to the host, and the buffers of devices that keep theirs there.
    std::uint64_t hostImages = std::uint64_t(settings_.width) * settings_.height * hostBytesPerPixel(denoises(settings_), settings_.aov);
    std::uint64_t hostBuffers = 0;
    for (std::size_t d = 0; d < devices_.size(); ++d) {
        hostBuffers += devices_[d]->buffersInHostMemory() ? plans[d].totalBytes() : 0;
    }
    if (std::uint64_t available = availableHostMemory(); hostImages + hostBuffers > available) {
        throw InputError(std::string(settings_.aov ? "the image and its auxiliary images need " : "the image needs ") +
                         formatMiB(hostImages) + " of host memory at " + std::to_string(settings_.width) + "x" +
                         std::to_string(settings_.height) + (hostBuffers > 0 ? " besides the buffers' " + formatMiB(hostBuffers) : "") +
                         ", more than the " + formatMiB(available) + " available; " +
                         whatToLower(settings_.aov ? BUFFER_PER_AOV_PIXEL : BUFFER_PER_PIXEL));
    }
    if (sceneDirty_) {
        for (std::size_t d = 0; d < devices_.size(); ++d) {
            devices_[d]->uploadScene(scene_, plans[d]);
        }
        sceneDirty_ = false;
    }
    bool same = std::equal(std::begin(budget.cells), std::end(budget.cells), std::begin(allocatedBudget_.cells)) &&
                allocatedWidth_ == settings_.width && allocatedHeight_ == settings_.height &&
                devicePlans_.size() == plans.size();
    for (std::size_t d = 0; same && d < plans.size(); ++d) {
        same = plans[d].scratchBytes == devicePlans_[d].scratchBytes;
        for (const BufferInfo& info : kBuffers) {
            same = same && (info.size == BUFFER_PER_SCENE ||
                            plans[d].elements[info.binding] == devicePlans_[d].elements[info.binding]);
        }
    }
    if (!same) {
        for (std::size_t d = 0; d < devices_.size(); ++d) {
            devices_[d]->allocate(plans[d], budget, settings_.width, settings_.height);
        }
        allocatedBudget_ = budget;
        allocatedWidth_ = settings_.width;
        allocatedHeight_ = settings_.height;
    }
    devicePlans_ = plans;
    plan_ = plans.front();
    budget_ = budget;
    allocationDirty_ = false;
}

void Renderer::renderFrame() {
    // A first frame that lost photons runs again with room for them: it replaces the
    // accumulation, so nothing of the short frame remains. Later frames keep what they have.
    for (bool first = true;; first = false) {
        const FrameParams& params = beginFrame();
        if (endFrame(runFrame(params), first)) {
            break;
        }
    }
}

void Renderer::recordFrame() {
    if (devices_.size() != 1) {
        throw std::logic_error("recordFrame: a frame the caller submits runs on one device");
    }
    devices_.front()->beginStages(params_);
    runStages(*devices_.front(), params_, false, 0, STAGE_COUNT);
    devices_.front()->submitStages();
}

FrameResult Renderer::runFrame(const FrameParams& params, bool denoiseOnly) {
    exchange_ = Exchange{};
    if ((devices_.size() > 1 || collective_->processes() > 1) && !denoiseOnly) {
        return runSharedFrame(params);
    }
    Device& device = *devices_.front();
    device.beginStages(params);
    runStages(device, params, denoiseOnly, 0, STAGE_COUNT);
    device.submitStages();
    return device.endStages();
}

// Each device its share of the paths, all at once where they run apart (GPUs); the photons into
// the first device's maps; the rest of the frame there.
FrameResult Renderer::runSharedFrame(const FrameParams& params) {
    std::uint32_t n = static_cast<std::uint32_t>(devices_.size());
    std::vector<FrameParams> shares(n, params);
    std::vector<Device*> devices;
    for (std::uint32_t d = 0; d < n; ++d) {
        splitPaths(shares[d], {d, n});
        devices.push_back(devices_[d].get());
        devices[d]->beginStages(shares[d]);
        runStages(*devices[d], shares[d], false, STAGE_TRACE_PHOTONS, STAGE_TRACE_PHOTONS + 1);
        devices[d]->submitStages();
    }
    std::vector<FrameResult> results;
    for (Device* device : devices) {
        results.push_back(device->endStages());
    }
    exchange_ = collective_->gatherPhotons(devices, shares, results);

    FrameResult frame = results.front();
    if (collective_->leads()) {
        Device& root = *devices.front();
        root.beginStages(shares.front(), true);
        runStages(root, shares.front(), false, STAGE_TRACE_PHOTONS + 1, STAGE_COUNT);
        root.submitStages();
        frame = root.endStages();
    }
    collective_->shareResult(frame);
    // The photon pass took as long as its slowest device where the devices run side by side, and
    // their sum where they take turns on the host's cores.
    double trace = 0.0;
    for (std::uint32_t d = 0; d < n; ++d) {
        double ms = results[d].ms[STAGE_TRACE_PHOTONS];
        trace = devices[d]->runsOnCpu() ? trace + ms : std::max(trace, ms);
    }
    frame.ms[STAGE_TRACE_PHOTONS] = trace;  // this process's photon pass; the rest is the leader's
    return frame;
}

// After beginStages(): a whole frame is stages [0, STAGE_COUNT); a part of one runs [first, last)
// and skips the others.
void Renderer::runStages(Device& device, const FrameParams& params, bool denoiseOnly, std::uint32_t first,
                         std::uint32_t last) {
    for (const StageInfo& stage : kStages) {
        bool denoise = stage.id == STAGE_DENOISE;
        bool optional = denoise || stage.id == STAGE_REPROJECT;
        std::uint32_t flag = denoise ? FLAG_DENOISE : FLAG_REPROJECT;
        bool runs = denoiseOnly ? denoise : !optional || (params.flags & flag) != 0u;
        if (runs && stage.id >= first && stage.id < last) {
            device.runStage(stage.id, params);
        } else {
            device.skipStage(stage.id);
        }
    }
}

void Renderer::denoiseImage() {
    if (accumulated_ == 0 || denoisedFrames_ == accumulated_ || !denoises(settings_)) {
        return;
    }
    FrameParams params = params_;
    params.flags |= FLAG_DENOISE;
    FrameResult result = runFrame(params, true);
    stats_.ms[STAGE_DENOISE] = result.ms[STAGE_DENOISE];
    denoisedFrames_ = accumulated_;
}

void Renderer::measureRadii() {
    if (!footprintsDirty_) {
        return;
    }
    footprints_ = measureFootprints(scene_, camera_, settings_);
    FrameRadii radii = firstFrameRadii(scene_, settings_, footprints_, planPhotons(scene_, settings_));
    validateForScene(settings_, scene_, radii);
    policy_.start(radii);
    footprintsDirty_ = false;
}

const FrameParams& Renderer::beginFrame() {
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

bool Renderer::endFrame(const FrameResult& result, bool mayRepeat) {
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
    stats_.exchange = exchange_;
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

bool Renderer::growPhotonMaps() {
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

void Renderer::requireLeader(const char* what) const {
    if (!collective_->leads()) {
        throw std::logic_error(std::string(what) + ": the image is the first process's (process " +
                               std::to_string(collective_->process()) + " of " +
                               std::to_string(collective_->processes()) + " asked)");
    }
}

Image Renderer::image() {
    requireLeader("image");
    if (accumulated_ == 0) {
        return Image(settings_.width, settings_.height);
    }
    if (!denoises(settings_)) {
        return readImage(BINDING_ACCUMULATION);
    }
    denoiseImage();
    return readImage(BINDING_DENOISED);
}

Image Renderer::rawImage() {
    requireLeader("rawImage");
    if (accumulated_ == 0) {
        return Image(settings_.width, settings_.height);
    }
    return readImage(BINDING_ACCUMULATION);
}

Image Renderer::readFrame() { return readImage(BINDING_FRAME); }

Image Renderer::readImage(std::uint32_t binding) {
    requireLeader("readImage");
    Image image(allocatedWidth_, allocatedHeight_);
    if (!image.pixels.empty()) {
        devices_.front()->readBuffer(binding, 0, image.pixels.size() * sizeof(glm::vec4), image.pixels.data());
    }
    return image;
}

template <typename T>
std::vector<T> Renderer::readPerPixel(std::uint32_t binding) {
    requireLeader("readPerPixel");
    std::vector<T> elements(std::size_t(allocatedWidth_) * allocatedHeight_);
    if (!elements.empty()) {
        devices_.front()->readBuffer(binding, 0, elements.size() * sizeof(T), elements.data());
    }
    return elements;
}

std::vector<HitPoint> Renderer::readHitPoints() { return readPerPixel<HitPoint>(BINDING_HIT_POINTS); }

std::vector<SppmPixel> Renderer::readSppmPixels() { return readPerPixel<SppmPixel>(BINDING_SPPM_PIXELS); }

std::vector<PixelAov> Renderer::readAovs() {
    if (!keepsAovs(settings_) || accumulated_ == 0) {
        return {};
    }
    return readPerPixel<PixelAov>(BINDING_AOVS);
}

PhotonMaps Renderer::readPhotonMaps() {
    requireLeader("readPhotonMaps");
    PhotonMaps maps;
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        const GridParams& grid = params_.grids[m];
        std::uint32_t stored = std::min(stats_.stored[m], grid.photonCapacity);
        maps.stored[m].resize(stored);
        if (stored > 0) {
            devices_.front()->readBuffer(BINDING_SORTED_PHOTONS, std::uint64_t(grid.photonOffset) * sizeof(MapPhoton),
                       std::uint64_t(stored) * sizeof(MapPhoton), maps.stored[m].data());
        }
        maps.photons[m].reserve(stored);
        for (const MapPhoton& p : maps.stored[m]) {
            maps.photons[m].push_back(decodeMapPhoton(p, grid));
        }
        maps.cellStart[m].resize(std::size_t(grid.cellCount) + 1);
        devices_.front()->readBuffer(BINDING_CELL_START, std::uint64_t(grid.cellOffset) * sizeof(std::uint32_t),
                   maps.cellStart[m].size() * sizeof(std::uint32_t), maps.cellStart[m].data());
    }
    return maps;
}

}  // namespace photon
