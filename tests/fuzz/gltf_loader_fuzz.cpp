// libFuzzer target for the glTF loader, .gltf text or .glb by its magic (model_loader_fuzz.h says
// what an input is).
#include "model_loader_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    bool binary = size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
    return photon::fuzz::loadModel(data, size, binary ? "fuzz.glb" : "fuzz.gltf");
}
