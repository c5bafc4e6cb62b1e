#include "core/image/exr_writer.h"

#include <cstring>
#include <mutex>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfTiledOutputFile.h>

#include "core/system/error.h"
#include "core/system/parallel.h"

namespace photon {
namespace {

constexpr int kTileSize = 128;

// OpenEXR's output stream into memory: the file goes to disk whole through writeOutputFile. OpenEXR
// seeks back to fill in the chunk offsets once the chunks are written.
class MemoryStream : public Imf::OStream {
public:
    explicit MemoryStream(std::size_t expected) : Imf::OStream("memory") { bytes_.reserve(expected); }
    void write(const char c[], int n) override {
        if (at_ + std::size_t(n) > bytes_.size()) {
            bytes_.resize(at_ + std::size_t(n));
        }
        std::memcpy(&bytes_[at_], c, std::size_t(n));
        at_ += std::size_t(n);
    }
    std::uint64_t tellp() override { return at_; }
    void seekp(std::uint64_t at) override { at_ = std::size_t(at); }
    std::string take() { return std::move(bytes_); }

private:
    std::string bytes_;
    std::size_t at_ = 0;
};

Imf::Compression openExrCompression(ExrCompression c) {
    switch (c) {
        case ExrCompression::None: return Imf::NO_COMPRESSION;
        case ExrCompression::Rle: return Imf::RLE_COMPRESSION;
        case ExrCompression::Zips: return Imf::ZIPS_COMPRESSION;
        case ExrCompression::Zip: return Imf::ZIP_COMPRESSION;
        case ExrCompression::Piz: return Imf::PIZ_COMPRESSION;
    }
    return Imf::RLE_COMPRESSION;
}

}  // namespace

const char* toString(ExrLayout l) { return l == ExrLayout::Tiles ? "tiles" : "scan lines"; }

const char* toString(ExrCompression c) {
    switch (c) {
        case ExrCompression::None: return "none";
        case ExrCompression::Rle: return "rle";
        case ExrCompression::Zips: return "zips";
        case ExrCompression::Zip: return "zip";
        case ExrCompression::Piz: return "piz";
    }
    return "?";
}

std::string encodeExr(const Image& image, ExrCompression compression, ExrLayout layout, const std::vector<ExrLayer>& layers) {
    // OpenEXR compresses blocks of scan lines in its global thread pool, which has no threads
    // until asked for: one per hardware thread, as parallelFor has.
    static std::once_flag poolStarted;
    std::call_once(poolStarted, [] { Imf::setGlobalThreadCount(int(workerThreads())); });
    try {
        Imf::Header header(int(image.width), int(image.height));
        header.compression() = openExrCompression(compression);
        Imf::FrameBuffer frame;
        const std::size_t pixel = sizeof(glm::vec4);
        std::size_t channels = 0;
        // Straight from the images' RGBA pixels: OpenEXR gathers each channel itself.
        auto insert = [&](const std::string& name, const Image& from, int c) {
            if (from.width != image.width || from.height != image.height) {
                throw std::invalid_argument("layer " + name + " is not the image's size");
            }
            header.channels().insert(name, Imf::Channel(Imf::FLOAT));
            char* first = const_cast<char*>(reinterpret_cast<const char*>(&from.pixels[0][c]));
            frame.insert(name, Imf::Slice(Imf::FLOAT, first, pixel, pixel * image.width));
            channels += 1;
        };
        const char* names[3] = {"R", "G", "B"};
        for (int c = 0; c < 3; ++c) {
            insert(names[c], image, c);
        }
        for (const ExrLayer& layer : layers) {
            for (std::size_t c = 0; c < layer.channels.size() && c < 4; ++c) {
                insert(layer.name + "." + layer.channels[c], *layer.image, int(c));
            }
        }
        MemoryStream stream(image.pixels.size() * channels * sizeof(float) + 4096);
        if (layout == ExrLayout::Tiles) {
            header.setTileDescription(Imf::TileDescription(kTileSize, kTileSize, Imf::ONE_LEVEL));
            Imf::TiledOutputFile file(stream, header);
            file.setFrameBuffer(frame);
            file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
        } else {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(frame);
            file.writePixels(int(image.height));
        }
        return stream.take();
    } catch (const std::exception& e) {
        throw RuntimeError(std::string("cannot encode the EXR image: ") + e.what());
    }
}

}  // namespace photon
