// libFuzzer target for the OBJ + MTL loader (model_loader_fuzz.h says what an input is).
#include "model_loader_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return photon::fuzz::loadModel(data, size, "fuzz.obj");
}
