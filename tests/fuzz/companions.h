// Fuzz inputs that carry files: the main text, then after a line "#--- name" each the bytes of a
// file it references (an MTL, an image, a .bin buffer, a model file of a scene's mesh object).
#pragma once

#include <map>
#include <string>

#include "core/loaders/model_loader.h"
#include "core/system/error.h"

namespace photon::fuzz {

using Companions = std::map<std::string, std::string>;

// Splits `input` into the main text (returned) and its companion files.
inline std::string splitCompanions(const std::string& input, Companions& companions) {
    const std::string marker = "\n#--- ";
    std::size_t cut = input.find(marker);
    std::string main = input.substr(0, cut);
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
    return main;
}

// Reads the companions only (a missing one fails as a missing file does).
inline FileReader companionReader(const Companions& companions) {
    return [&companions](const std::string& name, const char* what) {
        auto it = companions.find(name);
        if (it == companions.end()) {
            throw InputError(name + ": cannot open the " + std::string(what));
        }
        return it->second;
    };
}

}  // namespace photon::fuzz
