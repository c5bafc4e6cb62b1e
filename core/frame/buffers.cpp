#include "core/frame/buffers.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "core/system/error.h"
#include "shared/photon_map.h"

namespace photon {

static_assert(BUFFER_SIZE_CLASS_COUNT == 11u, "a new BUFFER_PER_* class needs its case in planBuffers and whatToLower");

std::uint64_t BufferPlan::bytes(std::uint32_t binding) const {
    std::uint64_t element = binding == BINDING_PARAMS ? sizeof(FrameParams) : bufferInfo(binding).elementBytes;
    return elements[binding] * element;
}

std::uint64_t BufferPlan::totalBytes() const {
    std::uint64_t total = scratchBytes;
    for (std::uint32_t b = 0; b < BINDING_COUNT; ++b) {
        total += bytes(b);
    }
    return total;
}

BufferPlan planBuffers(const Scene& scene, const PhotonBudget& budget, std::uint32_t width, std::uint32_t height) {
    BufferPlan plan;
    plan.elements[BINDING_PARAMS] = 1;
    for (const BufferInfo& info : kBuffers) {
        std::uint64_t n = 0;
        switch (info.size) {
            case BUFFER_PER_SCENE: n = std::max<std::uint64_t>(sceneArray(scene, info.binding).count, 1); break;
            case BUFFER_PER_PHOTON: n = std::max<std::uint64_t>(budget.totalCapacity(), 1); break;
            case BUFFER_PER_CELL: n = budget.totalCellEntries(); break;
            case BUFFER_PER_PIXEL: n = std::uint64_t(width) * height; break;
            case BUFFER_PER_COUNTER: n = COUNTER_COUNT; break;
            case BUFFER_PER_SPPM_PIXEL: n = budget.sppm ? std::uint64_t(width) * height : 1; break;
            case BUFFER_PER_AOV_PIXEL: n = budget.aovs ? std::uint64_t(width) * height : 1; break;
            case BUFFER_PER_DENOISE_PIXEL: n = budget.denoise ? std::uint64_t(width) * height : 1; break;
            case BUFFER_PER_DENOISE_PLANE: n = budget.denoise ? std::uint64_t(DENOISE_PLANES) * width * height : 1; break;
            case BUFFER_PER_HISTORY_PIXEL: n = budget.history ? std::uint64_t(width) * height : 1; break;
            case BUFFER_PER_ORDERED_PHOTON: n = budget.deterministic ? std::max<std::uint64_t>(ORDER_ARRAYS * std::uint64_t(budget.totalCapacity()), 1) : 1; break;
            default: throw std::logic_error(std::string("buffer ") + info.name + ": unknown size class");
        }
        plan.elements[info.binding] = n;
    }
    return plan;
}

void keepPhotonPassBuffers(BufferPlan& plan) {
    for (const BufferInfo& info : kBuffers) {
        bool traced = info.size == BUFFER_PER_SCENE || info.binding == BINDING_PHOTONS || info.binding == BINDING_COUNTERS;
        if (!traced) {
            plan.elements[info.binding] = 1;
        }
    }
}

void resizeChangedBuffers(const BufferPlan& plan, const std::function<bool(std::uint32_t, std::uint64_t)>& holds,
                          const std::function<void(std::uint32_t, std::uint64_t)>& resize) {
    std::vector<std::uint32_t> changed;
    for (const BufferInfo& info : kBuffers) {
        if (info.size != BUFFER_PER_SCENE && !holds(info.binding, plan.bytes(info.binding))) {
            changed.push_back(info.binding);
            resize(info.binding, 0);
        }
    }
    for (std::uint32_t binding : changed) {
        resize(binding, plan.bytes(binding));
    }
}

void forEachSceneBuffer(const Scene& scene, const BufferPlan& plan,
                        const std::function<void(std::uint32_t, const void*, std::uint64_t)>& upload) {
    for (const BufferInfo& info : kBuffers) {
        if (info.size != BUFFER_PER_SCENE) {
            continue;
        }
        std::uint64_t bytes = plan.bytes(info.binding);
        HostArray array = sceneArray(scene, info.binding);
        std::uint64_t arrayBytes = array.count * info.elementBytes;
        if (arrayBytes == bytes) {
            upload(info.binding, array.data, bytes);
            continue;
        }
        std::vector<unsigned char> padded(bytes, 0);
        if (arrayBytes > 0) {
            std::memcpy(padded.data(), array.data, std::min(arrayBytes, bytes));
        }
        upload(info.binding, padded.data(), bytes);
    }
}

const char* whatToLower(std::uint32_t sizeClass) {
    switch (sizeClass) {
        case BUFFER_PER_SCENE: return "simplify the scene";
        case BUFFER_PER_PHOTON: return "lower the photons per frame (--photons) or the photon capacity per path";
        case BUFFER_PER_CELL: return "lower the photons per frame (--photons) or the bounded grid's resolution";
        case BUFFER_PER_PIXEL: return "lower the resolution (--width, --height)";
        case BUFFER_PER_COUNTER: return "nothing can be lowered";
        case BUFFER_PER_SPPM_PIXEL: return "lower the resolution (--width, --height)";
        case BUFFER_PER_AOV_PIXEL: return "lower the resolution (--width, --height) or keep no auxiliary images (--denoise off, --no-aov)";
        case BUFFER_PER_DENOISE_PIXEL: return "lower the resolution (--width, --height) or turn the denoiser off (--denoise off)";
        case BUFFER_PER_DENOISE_PLANE: return "lower the resolution (--width, --height) or turn the denoiser off (--denoise off)";
        case BUFFER_PER_HISTORY_PIXEL:
            return "lower the resolution (--width, --height) or restart the image when the camera moves (--no-reproject)";
        case BUFFER_PER_ORDERED_PHOTON:
            return "lower the photons per frame (--photons) or let GPUs order the maps as they come (--no-deterministic)";
    }
    throw std::logic_error("unknown buffer size class");
}

const char* whatToLowerFor(std::uint32_t binding) {
    if (binding == BINDING_DENSITIES) {
        return "lower the density grids' resolution (a medium's \"grid\": {\"resolution\": ...}, 256 by default)";
    }
    return whatToLower(bufferInfo(binding).size);
}

std::uint64_t hostBytesPerPixel(bool denoise, bool aov) {
    return kHostBytesPerPixel + (denoise ? sizeof(glm::vec4) : 0u) + (aov ? sizeof(PixelAov) + 4 * sizeof(glm::vec4) : 0u);
}

std::uint64_t availableHostMemory() {
    std::uint64_t page = std::uint64_t(sysconf(_SC_PAGESIZE));
    std::uint64_t available = std::uint64_t(sysconf(_SC_PHYS_PAGES)) * page;
    std::ifstream meminfo("/proc/meminfo");
    for (std::string key; meminfo >> key;) {
        std::uint64_t kib = 0;
        meminfo >> kib;
        if (key == "MemAvailable:") {
            available = std::min(available, kib * 1024);
            break;
        }
        meminfo.ignore(256, '\n');
    }
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
        std::uint64_t mapped = 0;
        std::ifstream statm("/proc/self/statm");
        statm >> mapped;
        mapped *= page;
        available = std::min<std::uint64_t>(available, limit.rlim_cur > mapped ? limit.rlim_cur - mapped : 0);
    }
    return available;
}

std::string formatMiB(std::uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.1f MiB", double(bytes) / (1024.0 * 1024.0));
    return text;
}

void checkMemory(const BufferPlan& plan, const MemoryLimits& limits, std::uint32_t width, std::uint32_t height) {
    std::string size = " at " + std::to_string(width) + "x" + std::to_string(height);
    std::uint32_t largest = BINDING_PARAMS;
    for (std::uint32_t b = 1; b < BINDING_COUNT; ++b) {
        const BufferInfo& info = bufferInfo(b);
        if (limits.perBuffer > 0 && plan.bytes(b) > limits.perBuffer) {
            throw InputError("buffer '" + std::string(info.name) + "' needs " + formatMiB(plan.bytes(b)) +
                             (info.size == BUFFER_PER_SCENE ? "" : size) + ", more than the " +
                             formatMiB(limits.perBuffer) + " one buffer may span on " + limits.device + " (" +
                             limits.perBufferLimit + "); " + whatToLowerFor(b));
        }
        if (plan.bytes(b) > plan.bytes(largest)) {
            largest = b;
        }
    }
    if (plan.totalBytes() > limits.total) {
        const BufferInfo& info = bufferInfo(largest);
        throw InputError("the buffers need " + formatMiB(plan.totalBytes()) + size + ", more than the " +
                         formatMiB(limits.total) + " of " + limits.memory + " on " + limits.device +
                         "; the largest is '" + info.name + "' (" + formatMiB(plan.bytes(largest)) + "): " +
                         whatToLowerFor(largest));
    }
}

}  // namespace photon
