#include "core/render/render.h"

#include <chrono>

#include "core/render/devices.h"
#include "core/settings/setting_specs.h"

namespace photon {

RenderResult render(Scene scene, RenderSettings settings, const RenderJob& job, const RenderObserver& observer) {
    validateSettings(settings);
    auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    std::unique_ptr<Renderer> renderer = createRenderer(job.backend, job.device);
    choosePhotons(settings, renderer->runsOnCpu());
    renderer->setScene(std::move(scene));
    renderer->setSettings(settings);
    renderer->prepare();

    RenderResult result;
    result.backend = renderer->name();
    result.device = renderer->deviceName();
    bool timed = job.seconds > 0.0;
    std::uint32_t maxFrames = timed && !job.framesCap ? 0xffffffffu : settings.frames;
    for (std::uint32_t f = 0; f < maxFrames; ++f) {
        renderer->renderFrame();
        result.times.push_back(renderer->lastFrameStats().ms);
        double seconds = elapsed();
        if (observer.frame) {
            observer.frame(f + 1, seconds);
        }
        // Processes rendering together stop after the same frame: when any asks, or the leader's
        // time is spent.
        int request = observer.cancel ? observer.cancel() : 0;
        StopVote vote = renderer->agreeToStop(request, timed && seconds >= job.seconds);
        if (vote.stop) {
            result.cancelled = vote.request;
            break;
        }
    }
    result.leader = renderer->leads();
    result.processes = renderer->processes();
    if (!result.leader) {
        result.last = renderer->lastFrameStats();
        result.seconds = elapsed();
        return result;  // the image is the leader's
    }
    if (observer.finished) {
        observer.finished(*renderer);
    }
    result.image = renderer->image();
    if (!result.times.empty()) {
        result.times.back()[STAGE_DENOISE] = renderer->lastFrameStats().ms[STAGE_DENOISE];  // run by image(), once
    }
    result.last = renderer->lastFrameStats();
    if (denoises(settings)) {
        result.raw = renderer->rawImage();
    }
    if (settings.aov) {
        result.aovs = aovImages(renderer->readAovs(), settings.width, settings.height, std::uint32_t(result.times.size()));
    }
    result.seconds = elapsed();
    return result;
}

}  // namespace photon
