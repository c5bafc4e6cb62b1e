#include "core/render/render.h"

#include <chrono>

#include "core/render/devices.h"
#include "core/settings/setting_specs.h"

namespace photon {

RenderResult render(Scene scene, RenderSettings settings, const RenderJob& job, const RenderObserver& observer) {
    validateSettings(settings);
    auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    std::unique_ptr<Backend> backend = createBackend(job.backend, job.device);
    choosePhotons(settings, backend->runsOnCpu());
    backend->setScene(std::move(scene));
    backend->setSettings(settings);
    backend->prepare();

    RenderResult result;
    result.backend = backend->name();
    result.device = backend->deviceName();
    bool timed = job.seconds > 0.0;
    std::uint32_t maxFrames = timed && !job.framesCap ? 0xffffffffu : settings.frames;
    for (std::uint32_t f = 0; f < maxFrames; ++f) {
        backend->renderFrame();
        result.times.push_back(backend->lastFrameStats().ms);
        double seconds = elapsed();
        if (observer.frame) {
            observer.frame(f + 1, seconds);
        }
        if (observer.cancel && observer.cancel()) {
            result.cancelled = true;
            break;
        }
        if (timed && seconds >= job.seconds) {
            break;
        }
    }
    if (observer.finished) {
        observer.finished(*backend);
    }
    result.image = backend->image();
    if (!result.times.empty()) {
        result.times.back()[STAGE_DENOISE] = backend->lastFrameStats().ms[STAGE_DENOISE];  // run by image(), once
    }
    result.last = backend->lastFrameStats();
    if (denoises(settings)) {
        result.raw = backend->rawImage();
    }
    if (settings.aov) {
        result.aovs = aovImages(backend->readAovs(), settings.width, settings.height, std::uint32_t(result.times.size()));
    }
    result.seconds = elapsed();
    return result;
}

}  // namespace photon
