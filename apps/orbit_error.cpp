#include "apps/orbit_error.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "core/frame/glass_pixels.h"
#include "core/image/image_error.h"

namespace photon {
namespace {

constexpr double kFrameSeconds = 1.0 / 60.0;  // as photon-view --frames

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    std::size_t n = v.size();
    return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

double brightest(const Image& image) {
    double peak = 0.0;
    for (const glm::vec4& p : image.pixels) {
        peak = std::max(peak, luminance(p));
    }
    return peak;
}

// The images of one moving run at the sample frames, and its brightest pixel of every frame.
struct Run {
    std::vector<Image> raw, denoised;
    double brightest = 0.0;
    double frameMs = 0.0;      // median stage time of a frame
    double reprojectMs = 0.0;  // ... and of its reproject stage
    double denoiseMs = 0.0;    // ... and of its denoise stage
};

Run moveAlong(Renderer& backend, const Scene& scene, const RenderSettings& settings, const OrbitMeasurement& m,
              const std::vector<std::uint32_t>& samples) {
    backend.setDenoiseEachFrame(true);  // as a viewer: every frame is shown
    backend.setScene(scene);
    backend.setSettings(settings);
    Run run;
    std::vector<double> ms, reproject, denoise;
    std::size_t next = 0;
    for (std::uint32_t f = 0; f < m.frames; ++f) {
        CameraDesc camera = cameraAt(m.path, scene.camera, f * kFrameSeconds);
        if (f == 0) {
            backend.setCamera(camera);
        } else {
            backend.moveCamera(camera);  // without --reproject the same as setCamera: a restart
        }
        backend.renderFrame();
        ms.push_back(backend.lastFrameStats().ms.total());
        reproject.push_back(backend.lastFrameStats().ms[STAGE_REPROJECT]);
        denoise.push_back(backend.lastFrameStats().ms[STAGE_DENOISE]);
        Image shown = backend.image();
        run.brightest = std::max(run.brightest, brightest(shown));
        if (next < samples.size() && samples[next] == f) {
            run.raw.push_back(backend.rawImage());
            run.denoised.push_back(std::move(shown));
            ++next;
        }
    }
    run.frameMs = median(ms);
    run.reprojectMs = median(reproject);
    run.denoiseMs = median(denoise);
    return run;
}

}  // namespace

nlohmann::json measureOrbit(const std::function<std::unique_ptr<Renderer>()>& makeBackend, const Scene& scene,
                            const RenderSettings& settings, const OrbitMeasurement& m) {
    std::vector<std::uint32_t> samples;
    for (std::uint32_t i = 1; i <= m.samples; ++i) {
        samples.push_back(std::max(1u, std::uint32_t(std::uint64_t(m.frames) * i / m.samples)) - 1u);
    }
    samples.erase(std::unique(samples.begin(), samples.end()), samples.end());

    // The references: each sample frame's camera held still.
    std::vector<Image> references;
    double referencePeak = 0.0;
    {
        std::unique_ptr<Renderer> backend = makeBackend();
        RenderSettings still = settings;
        still.denoise = Denoise::Off;
        still.reproject = false;
        backend->setScene(scene);
        backend->setSettings(still);
        for (std::uint32_t f : samples) {
            backend->setCamera(cameraAt(m.path, scene.camera, f * kFrameSeconds));
            for (std::uint32_t i = 0; i < m.referenceFrames; ++i) {
                backend->renderFrame();
            }
            references.push_back(backend->rawImage());
            referencePeak = std::max(referencePeak, brightest(references.back()));
        }
    }

    RenderSettings restart = settings;
    restart.reproject = false;
    RenderSettings carry = settings;
    carry.reproject = true;
    std::unique_ptr<Renderer> backend = makeBackend();
    Run before = moveAlong(*backend, scene, restart, m, samples);
    Run after = moveAlong(*backend, scene, carry, m, samples);

    std::printf("orbit of %.1f s, %u frames of 1/60 s, %u references of %u frames\n", m.path.seconds, m.frames,
                unsigned(samples.size()), m.referenceFrames);
    std::printf("%6s  %-29s %-29s %-29s %-29s\n", "", "restart raw", "restart denoised", "reproject raw",
                "reproject denoised");
    std::printf("%6s ", "frame");
    for (int i = 0; i < 4; ++i) {
        std::printf(" %9s %9s %7s ", "whole", "away", "ssim");
    }
    std::printf("\n");
    nlohmann::json rows = nlohmann::json::array();
    const char* names[4] = {"restart_raw", "restart_denoised", "reproject_raw", "reproject_denoised"};
    std::vector<double> whole[4], away[4], ssim[4];
    std::vector<double> glass[4];
    for (std::size_t i = 0; i < samples.size(); ++i) {
        CameraDesc camera = cameraAt(m.path, scene.camera, samples[i] * kFrameSeconds);
        QualityMasks masks(references[i], glassPixels(scene, camera, settings));
        const Image* images[4] = {&before.raw[i], &before.denoised[i], &after.raw[i], &after.denoised[i]};
        if (!m.imagesDir.empty()) {
            std::string frame = std::to_string(samples[i] + 1);
            writeImage(m.imagesDir + "/reference-" + frame + ".pfm", references[i], 0.0f, Tonemap::Clamp);
            for (int k = 0; k < 4; ++k) {
                writeImage(m.imagesDir + "/" + names[k] + "-" + frame + ".pfm", *images[k], 0.0f, Tonemap::Clamp);
            }
        }
        nlohmann::json row = {{"frame", samples[i] + 1}};
        std::printf("%6u ", samples[i] + 1);
        for (int k = 0; k < 4; ++k) {
            Quality q = measureQuality(*images[k], references[i], masks);
            whole[k].push_back(q.whole);
            away[k].push_back(q.away);
            ssim[k].push_back(q.ssim);
            glass[k].push_back(q.glass);
            row[names[k]] = {{"rmse", q.whole}, {"rmse_away_from_focus", q.away}, {"ssim", q.ssim},
                             {"rmse_glass", q.glass}, {"glass_off_25", q.glassOff}};
            std::printf(" %8.2f%% %8.2f%% %7.4f ", 100.0 * q.whole, 100.0 * q.away, q.ssim);
        }
        std::printf("\n");
        rows.push_back(row);
    }
    nlohmann::json medians;
    std::printf("%6s ", "median");
    for (int k = 0; k < 4; ++k) {
        medians[names[k]] = {{"rmse", median(whole[k])}, {"rmse_away_from_focus", median(away[k])}, {"ssim", median(ssim[k])},
                             {"rmse_glass", median(glass[k])}};
        std::printf(" %8.2f%% %8.2f%% %7.4f ", 100.0 * median(whole[k]), 100.0 * median(away[k]), median(ssim[k]));
    }
    std::printf("\nmedian through glass:");
    for (int k = 0; k < 4; ++k) {
        std::printf(" %s %.2f%%", names[k], 100.0 * median(glass[k]));
    }
    std::printf("\nbrightest pixel shown / the references' brightest: restart %.2f, reproject %.2f; frame ms: restart "
                "%.3f, reproject %.3f (its reproject stage %.3f, denoise %.3f)\n",
                before.brightest / referencePeak, after.brightest / referencePeak, before.frameMs, after.frameMs,
                after.reprojectMs, after.denoiseMs);
    std::fflush(stdout);
    return {{"orbit_seconds", m.path.seconds}, {"frames", m.frames}, {"reference_frames", m.referenceFrames},
            {"samples", rows}, {"median", medians},
            {"brightest_ratio", {{"restart", before.brightest / referencePeak}, {"reproject", after.brightest / referencePeak}}},
            {"frame_ms", {{"restart", before.frameMs}, {"reproject", after.frameMs}}},
            {"reproject_stage_ms", after.reprojectMs}, {"denoise_stage_ms", after.denoiseMs}};
}

}  // namespace photon
