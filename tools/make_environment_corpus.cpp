// photon-make-environment-corpus: writes the seeds of the environment loader's fuzz target, one
// small file of each kind the loader reads, so that the fuzzer starts inside every decoder path
// (flat and run-length HDR, both magic lines; EXR in each compression, half and float, RGB and
// RGBA, both line orders). Its output is committed:
//   photon-make-environment-corpus tests/fuzz/corpus/environment_loader_fuzz
#include <cstdio>
#include <map>
#include <string>

#include "core/system/output_file.h"
#include "core/system/program.h"
#include "environment_files.h"

namespace photon {
namespace {

using tools::ExrCompression;
using tools::ExrType;

// Texels that differ everywhere, and a first row of one colour (runs for the run-length coders).
std::vector<glm::vec3> texels(int width, int height) {
    std::vector<glm::vec3> t;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            t.push_back(y == 0 ? glm::vec3(4.0f, 3.0f, 2.0f) : glm::vec3(0.5f + x, 0.25f * y, 1.0f / float(1 + x + y)));
        }
    }
    return t;
}

int run(int argc, char** argv) {
    if (argc != 2) {
        throw InputError("usage: photon-make-environment-corpus FOLDER");
    }
    std::map<std::string, std::string> files;
    files["flat.hdr"] = tools::hdrBytes(3, 2, texels(3, 2));
    files["rle.hdr"] = tools::hdrBytes(16, 4, texels(16, 4));
    files["rgbe.hdr"] = "#?RGBE" + files["flat.hdr"].substr(10);  // the other magic line
    files["none.exr"] = tools::exrBytes(3, 2, texels(3, 2), "RGB", ExrType::Float, ExrCompression::None);
    files["rle.exr"] = tools::exrBytes(4, 3, texels(4, 3), "RGBA", ExrType::Half, ExrCompression::Rle);
    files["zips.exr"] = tools::exrBytes(2, 2, texels(2, 2), "RGB", ExrType::Float, ExrCompression::Zips);
    files["zip.exr"] = tools::exrBytes(5, 20, texels(5, 20), "RGB", ExrType::Half, ExrCompression::Zip);
    files["piz.exr"] = tools::exrBytes(4, 40, texels(4, 40), "RGBA", ExrType::Float, ExrCompression::Piz);
    std::string decreasing = files["none.exr"];
    decreasing[tools::exrAttribute(decreasing, "lineOrder", "lineOrder")] = 1;  // DECREASING_Y
    files["decreasing.exr"] = decreasing;
    for (const auto& [name, bytes] : files) {
        std::string path = std::string(argv[1]) + "/" + name;
        writeOutputFile(path, bytes, "seed");
        std::fprintf(stderr, "photon-make-environment-corpus: %s, %zu bytes\n", path.c_str(), bytes.size());
    }
    return 0;
}

}  // namespace
}  // namespace photon

int main(int argc, char** argv) {
    return photon::runProgram("photon-make-environment-corpus", [&] { return photon::run(argc, argv); });
}
