// The library face (core/render/render.h): one call renders a scene as a backend driven frame by
// frame does, bit for bit; it stops on cancellation with the image so far, honours a time limit,
// and refuses bad settings before it makes a device.
#include <gtest/gtest.h>

#include "core/loaders/scene_loader.h"
#include "core/render/render.h"
#include "core/settings/setting_specs.h"
#include "backend_compare.h"
#include "test_render.h"

namespace photon {
namespace {

// The photon count given as a scene file or option gives it: render() chooses one for the device
// only where the settings leave it.
RenderSettings small(std::uint32_t frames) {
    RenderSettings s = test::sizedSettings(defaultScene().render, 48, 36, 4000);
    setSetting(s, *findSetting("photons"), "4000", "test");
    s.frames = frames;
    s.deterministic = true;
    return s;
}

RenderJob onCpu() {
    RenderJob job;
    job.backend = "cpu";
    return job;
}

TEST(RenderApi, OneCallEqualsABackendDrivenFrameByFrame) {
    RenderSettings settings = small(3);
    RenderResult result = render(defaultScene(), settings, onCpu());
    ASSERT_EQ(result.times.size(), 3u);
    EXPECT_FALSE(result.cancelled);
    EXPECT_EQ(result.backend, "cpu");
    EXPECT_EQ(test::differingPixels(result.image, test::renderOnCpu(defaultScene(), settings, 3)), 0u);
    EXPECT_GT(result.last.stored[MAP_GLOBAL], 0u);
}

TEST(RenderApi, ObserverSeesEveryFrameAndCancelsWithTheImageSoFar) {
    std::vector<std::uint32_t> seen;
    bool finished = false;
    RenderObserver observer;
    observer.frame = [&](std::uint32_t frames, double seconds) {
        seen.push_back(frames);
        EXPECT_GE(seconds, 0.0);
    };
    observer.cancel = [&] { return seen.size() == 2; };
    observer.finished = [&](Renderer& backend) { finished = backend.lastFrameStats().stored[MAP_GLOBAL] > 0; };
    RenderResult result = render(defaultScene(), small(10), onCpu(), observer);
    EXPECT_TRUE(result.cancelled);
    EXPECT_EQ(seen, (std::vector<std::uint32_t>{1, 2}));
    EXPECT_TRUE(finished);
    EXPECT_EQ(test::differingPixels(result.image, test::renderOnCpu(defaultScene(), small(2), 2)), 0u)
        << "the image of the two frames rendered";
}

TEST(RenderApi, TimeLimitRendersUntilItPassesAndFramesCapIt) {
    RenderJob job = onCpu();
    job.seconds = 0.05;
    RenderResult timed = render(defaultScene(), small(1), job);
    EXPECT_GE(timed.seconds, 0.05);
    EXPECT_GE(timed.times.size(), 1u);
    job.seconds = 1e3;
    job.framesCap = true;
    EXPECT_EQ(render(defaultScene(), small(2), job).times.size(), 2u) << "--frames caps --time";
}

TEST(RenderApi, ImagesBesideTheFinalOne) {
    RenderSettings settings = small(2);
    settings.denoise = Denoise::On;
    settings.aov = true;
    RenderResult result = render(defaultScene(), settings, onCpu());
    EXPECT_EQ(result.raw.pixels.size(), result.image.pixels.size()) << "the image before the denoiser";
    EXPECT_GT(test::differingPixels(result.raw, result.image), 0u);
    EXPECT_EQ(result.aovs.albedo.pixels.size(), result.image.pixels.size());
}

TEST(RenderApi, PhotonsNotGivenAreChosenForTheDevice) {
    RenderSettings settings = test::sizedSettings(defaultScene().render, 48, 36, 4000);
    settings.frames = 1;
    settings.deterministic = true;
    RenderResult result = render(defaultScene(), settings, onCpu());
    RenderSettings chosen = settings;
    choosePhotons(chosen, true);
    ASSERT_NE(chosen.photons, 4000u);
    EXPECT_EQ(test::differingPixels(result.image, test::renderOnCpu(defaultScene(), chosen, 1)), 0u)
        << "the CPU's photon count for 48x36, not the 4000 left unmarked in the settings";
}

TEST(RenderApi, BadSettingsAndBackendsAreRefused) {
    RenderSettings bad = small(1);
    bad.width = 0;
    EXPECT_THROW(render(defaultScene(), bad, onCpu()), InputError);
    RenderJob job;
    job.backend = "quantum";
    EXPECT_THROW(render(defaultScene(), small(1), job), InputError);
}

}  // namespace
}  // namespace photon
