// libFuzzer target for the environment map loader: the input is the bytes of a file (seeded with
// Radiance HDR and OpenEXR files in every encoding the loader reads), written to a file of this
// process's own and loaded as a scene's map is. It must raise InputError, or give a map of
// width × height texels within the maxima, every one finite and ≥ 0. Anything else (another
// exception, a crash, a sanitizer report, a leak, a hang) is a bug.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/loaders/environment_loader.h"
#include "core/system/error.h"

namespace {

// The file the inputs go through, removed when the fuzzer exits.
struct InputFile {
    std::string path = (std::filesystem::temp_directory_path() / ("photon-environment-fuzz-" + std::to_string(::getpid()))).string();
    ~InputFile() { std::remove(path.c_str()); }
};

bool valid(const photon::EnvironmentMap& map) {
    if (map.width < 1 || map.height < 1 || map.width > photon::kEnvironmentWidthMax ||
        map.height > photon::kEnvironmentHeightMax || map.texels.size() != std::size_t(map.width) * map.height) {
        return false;
    }
    for (const glm::vec3& t : map.texels) {
        for (int k = 0; k < 3; ++k) {
            if (!std::isfinite(t[k]) || t[k] < 0.0f) {
                return false;
            }
        }
    }
    return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static InputFile file;
    std::ofstream(file.path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
    try {
        photon::EnvironmentMap map = photon::loadEnvironmentMap(file.path);
        if (!valid(map)) {
            std::fprintf(stderr, "a map of %ux%u with %zu texels that are not all finite and >= 0\n", map.width, map.height,
                         map.texels.size());
            std::abort();
        }
    } catch (const photon::InputError& e) {
        // Rejected input: the expected outcome for most mutations.
        if (std::getenv("PHOTON_FUZZ_TRACE")) {
            std::fprintf(stderr, "refused: %s\n", e.what());
        }
    }
    return 0;
}
