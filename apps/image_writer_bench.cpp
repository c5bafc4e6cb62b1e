#include "apps/image_writer_bench.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <functional>

#include "core/frame/median.h"
#include "core/image/exr_writer.h"
#include "core/image/image.h"
#include "core/system/output_file.h"
#include "core/system/parallel.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

struct Writer {
    const char* extension;
    std::string compression;
    std::function<std::string(const Image&)> encode;
};

}  // namespace

void benchImageWriters(Renderer& backend, const Scene& scene,
                       const std::vector<std::pair<std::uint32_t, std::uint32_t>>& resolutions, std::uint32_t writes,
                       const std::string& folder) {
    float exposure = scene.render.exposure;
    Tonemap curve = scene.render.tonemap;
    std::vector<Writer> writers = {
        {"png", "igzip 1, sub, 32-row bands",
         [&](const Image& i) { return encodeImage(ImageFormat::Png, i, exposure, curve); }},
        {"pfm", "none", [&](const Image& i) { return encodeImage(ImageFormat::Pfm, i, exposure, curve); }},
    };
    for (ExrLayout l : {ExrLayout::Scanlines, ExrLayout::Tiles}) {
        for (ExrCompression c : {ExrCompression::Rle, ExrCompression::None, ExrCompression::Zips, ExrCompression::Zip,
                                 ExrCompression::Piz}) {
            bool chosen = c == ExrCompression::Rle && l == ExrLayout::Scanlines;
            std::string label = std::string(toString(c)) + ", float, " + toString(l) + (chosen ? " (default)" : "");
            writers.push_back({"exr", label, [c, l](const Image& i) { return encodeExr(i, c, l); }});
        }
    }
    std::printf("image writers: %s, %u threads, median of %u writes into %s\n", backend.deviceName().c_str(),
                workerThreads(), writes, folder.c_str());
    std::printf("%-6s %-34s %-10s %10s %10s %10s\n", "format", "compression", "resolution", "MB", "encode ms",
                "file ms");
    std::vector<std::string> written;
    for (auto [width, height] : resolutions) {
        RenderSettings settings = scene.render;
        settings.width = width;
        settings.height = height;
        settings.frames = 1;
        backend.setScene(scene);
        backend.setSettings(settings);
        backend.prepare();
        backend.renderFrame();
        Image image = backend.image();
        for (const Writer& w : writers) {
            std::string path = folder + "/photon-bench-image." + w.extension;
            std::vector<double> encodeMs;
            std::vector<double> fileMs;
            std::size_t size = 0;
            for (std::uint32_t i = 0; i <= writes; ++i) {
                Clock::time_point start = Clock::now();
                std::string bytes = w.encode(image);
                Clock::time_point encoded = Clock::now();
                writeOutputFile(path, bytes, "image");
                Clock::time_point done = Clock::now();
                size = bytes.size();
                if (i > 0) {  // the first write warms the thread pools and the tables up
                    encodeMs.push_back(msBetween(start, encoded));
                    fileMs.push_back(msBetween(start, done));
                }
            }
            written.push_back(path);
            std::printf("%-6s %-34s %4ux%-5u %10.2f %10.1f %10.1f\n", w.extension, w.compression.c_str(), width,
                        height, double(size) / 1e6, median(encodeMs), median(fileMs));
            std::fflush(stdout);
        }
    }
    for (const std::string& path : written) {
        ::unlink(path.c_str());
    }
}

}  // namespace photon
