// photon-make-mesh: writes a generated mesh as binary glTF, for benchmarks of any size (meshes
// are made when they are needed, not committed).
//   photon-make-mesh --shape bumpy-sphere|terrain|sphere --triangles 1000000 -o mesh.glb
#include <cmath>
#include <cstdio>

#include <CLI/CLI.hpp>

#include "core/loaders/json_node.h"
#include "core/system/error.h"
#include "core/system/output_file.h"
#include "core/system/program.h"
#include "glb_writer.h"
#include "mesh_shapes.h"

namespace photon {
namespace {

int run(int argc, char** argv) {
    CLI::App app{"Writes a generated mesh as binary glTF", "photon-make-mesh"};
    std::string shape = "bumpy-sphere";
    std::uint64_t triangles = 100000;
    std::string output;
    std::string material = R"({"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0, "roughnessFactor": 1}})";
    app.add_option("--shape", shape, "bumpy-sphere|terrain|sphere")->check(CLI::IsMember({"bumpy-sphere", "terrain", "sphere"}));
    app.add_option("--triangles", triangles, "About how many triangles")->check(CLI::Range(2ull, 100000000ull));
    app.add_option("--material", material, "The glTF material, as JSON");
    app.add_option("--output,-o", output, "The .glb file")->required();
    if (int code = parseCommandLine(app, argc, argv); code >= 0) {
        return code;
    }
    // Bad JSON is bad input (exit 2), found before the mesh is made.
    if (!parseJson(material, "--material").is_object()) {
        throw InputError("--material: must be a JSON object (a glTF material)");
    }
    checkOutputPath(output, "mesh");
    Mesh mesh = shape == "terrain" ? tools::terrain(triangles)
                : shape == "sphere"
                    ? tools::uvSphere(glm::vec3(0.0f), 1.0f, std::uint32_t(std::sqrt(double(triangles) / 4.0)) + 2,
                                      2 * (std::uint32_t(std::sqrt(double(triangles) / 4.0)) + 2), true)
                    : tools::bumpySphere(triangles);
    writeOutputFile(output, tools::glbFromMesh(mesh, material), "mesh");
    std::fprintf(stderr, "photon-make-mesh: %zu triangles, %zu vertices -> %s\n", mesh.triangles.size(),
                 mesh.positions.size(), output.c_str());
    return 0;
}

}  // namespace
}  // namespace photon

int main(int argc, char** argv) {
    return photon::runProgram("photon-make-mesh", [&] { return photon::run(argc, argv); });
}
