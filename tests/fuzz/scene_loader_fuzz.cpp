// libFuzzer target for the scene loader: every input must either load or raise InputError. Anything
// else that escapes (another exception, a crash, a sanitizer report, a timeout) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/loaders/scene_loader.h"
#include "core/system/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        photon::loadSceneJson(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    } catch (const photon::InputError&) {
        // Rejected input: the expected outcome for almost every mutation.
    }
    return 0;
}
