// The body of the model loader fuzz targets: the input is a model file, optionally followed by
// companion files after a line "#--- name" each (an MTL, a .bin buffer, an image), so that the
// fuzzer reaches what the model references. Every input must load as photon-render loads a model
// file (a scene of its own: finalized, which builds the BVH, with a camera and lights) and render
// to finite pixels (render_check.h), or raise InputError; anything else is a bug.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "companions.h"
#include "core/loaders/model_loader.h"
#include "core/system/error.h"
#include "render_check.h"

namespace photon::fuzz {

inline int loadModel(const std::uint8_t* data, std::size_t size, const std::string& path) {
    Companions companions;
    std::string model = splitCompanions(std::string(reinterpret_cast<const char*>(data), size), companions);
    FileReader read = companionReader(companions);
    try {
        // As photon-render renders a model file: its cameras and lights, or a framing camera and
        // suns; then rendered, so that its texture coordinates and textures are sampled too.
        Scene scene = loadModelScene(path, model, read);
        renderTiny(scene, scene.render);
    } catch (const InputError& e) {
        // Rejected input: the expected outcome for most mutations.
        if (std::getenv("PHOTON_FUZZ_TRACE")) {
            std::fprintf(stderr, "refused: %s\n", e.what());
        }
    }
    return 0;
}

}  // namespace photon::fuzz
