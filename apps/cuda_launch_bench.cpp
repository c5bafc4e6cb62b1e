#include "apps/cuda_launch_bench.h"

#include <chrono>
#include <cstdio>
#include <vector>

#include "core/frame/median.h"
#include "core/image/image.h"
#ifdef PHOTON_HAVE_CUDA
#include "cuda/cuda_device.h"
#endif

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// The CUDA backend's readback through pageable memory instead of pinned (no effect elsewhere).
void setPageableReadback([[maybe_unused]] Renderer& backend, [[maybe_unused]] bool pageable) {
#ifdef PHOTON_HAVE_CUDA
    LaunchConfig c = cudaLaunchConfig(backend.device());
    c.pinnedReadback = !pageable;
    setCudaLaunchConfig(backend.device(), c);
#endif
}

}  // namespace

void sweepLaunchShapes([[maybe_unused]] Renderer& backend, [[maybe_unused]] const std::function<void(const std::string&)>& measure) {
#ifdef PHOTON_HAVE_CUDA
    const LaunchConfig start = cudaLaunchConfig(backend.device());
    measure("default");
    for (std::uint32_t photonBlock : {64u, 128u, 256u}) {
        for (auto [bx, by] : {std::pair{8u, 8u}, {16u, 8u}, {32u, 4u}, {16u, 16u}, {32u, 8u}}) {
            LaunchConfig c = start;
            c.photonBlock = photonBlock;
            c.eyeBlockX = c.pixelBlockX = bx;
            c.eyeBlockY = c.pixelBlockY = by;
            setCudaLaunchConfig(backend.device(), c);
            measure(std::to_string(photonBlock) + "/" + std::to_string(bx) + "x" + std::to_string(by));
        }
    }
    // The sppm gather's other register caps, the rest as the backend has them.
    for (std::uint32_t registers : {64u, 128u}) {
        LaunchConfig c = start;
        c.gatherRegisters = registers;
        setCudaLaunchConfig(backend.device(), c);
        measure("gather-regs-" + std::to_string(registers));
    }
    setCudaLaunchConfig(backend.device(), start);
#endif
}

void timeReadback(Renderer& backend) {
    for (bool pinned : {true, false}) {
        setPageableReadback(backend, !pinned);
        std::vector<double> ms;
        for (int i = 0; i < 21; ++i) {
            Clock::time_point t = Clock::now();
            Image image = backend.image();
            ms.push_back(msSince(t));
        }
        std::printf("  image readback (%s memory): %.2f ms median of 21\n", pinned ? "pinned" : "pageable", median(ms));
    }
    setPageableReadback(backend, false);
}

double timePrimaryRays([[maybe_unused]] Renderer& backend, [[maybe_unused]] std::uint32_t width,
                       [[maybe_unused]] std::uint32_t height) {
#ifdef PHOTON_HAVE_CUDA
    PrimaryRayTiming t = timeCudaPrimaryRays(backend.device(), 21);
    double raysPerSecond = t.medianMs > 0 ? double(t.rays) / t.medianMs * 1e3 : 0.0;
    std::printf("  primary rays %ux%u: %.3f ms median of 21, %.2f G rays/s, %.1f%% hit\n", width, height, t.medianMs,
                raysPerSecond / 1e9, t.rays ? 100.0 * double(t.hits) / double(t.rays) : 0.0);
    return raysPerSecond;
#else
    return 0.0;
#endif
}

}  // namespace photon
