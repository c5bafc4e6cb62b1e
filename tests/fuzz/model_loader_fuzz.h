// The body of the model loader fuzz targets: the input is a model file, optionally followed by
// companion files after a line "#--- name" each (an MTL, a .bin buffer, an image), so that the
// fuzzer reaches what the model references. Every input must load (and its scene finalize, which
// builds the BVH over whatever geometry came in) or raise InputError; anything else is a bug.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

#include "core/error.h"
#include "core/model_loader.h"

namespace photon::fuzz {

inline int loadModel(const std::uint8_t* data, std::size_t size, const std::string& path) {
    std::string input(reinterpret_cast<const char*>(data), size);
    std::map<std::string, std::string> companions;
    const std::string marker = "\n#--- ";
    std::size_t cut = input.find(marker);
    std::string model = input.substr(0, cut);
    while (cut != std::string::npos) {
        std::size_t nameStart = cut + marker.size();
        std::size_t nameEnd = input.find('\n', nameStart);
        if (nameEnd == std::string::npos) {
            break;
        }
        std::size_t next = input.find(marker, nameEnd);
        companions[input.substr(nameStart, nameEnd - nameStart)] =
            input.substr(nameEnd + 1, next == std::string::npos ? std::string::npos : next - nameEnd - 1);
        cut = next;
    }
    FileReader read = [&](const std::string& name, const char* what) {
        auto it = companions.find(name);
        if (it == companions.end()) {
            throw InputError(name + ": cannot open the " + std::string(what));
        }
        return it->second;
    };
    try {
        Scene scene;
        ModelOptions options;
        options.cameraAndLights = true;
        addModel(scene, path, model, options, read);
        scene.finalize();
    } catch (const InputError&) {
        // Rejected input: the expected outcome for most mutations.
    }
    return 0;
}

}  // namespace photon::fuzz
