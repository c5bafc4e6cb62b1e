#include "core/loaders/scene_media.h"

#include <cmath>

#include "core/loaders/vdb_loader.h"
#include "core/system/error.h"

namespace photon {
namespace {

// A coefficient [1/scene unit]: one number for every channel, or an RGB array.
glm::vec3 coefficient(const JsonNode& node) {
    if (node.value().is_number()) {
        return glm::vec3(node.number(kNonNegative));
    }
    return node.rgb(kNonNegative);
}

// A medium's "grid": {"file": "smoke.vdb", "name": "density", "resolution": 256, "min": [...],
// "max": [...]}: an OpenVDB file's grid (its first float grid without a name), averaged down to
// at most `resolution` voxels along an axis, in the box the file places it or in min..max.
DensityGrid readDensityGrid(const JsonNode& node, const MediaFiles& files) {
    node.allowKeys({"file", "name", "resolution", "min", "max"});
    const std::string& name = node["file"].string();
    if (name.empty()) {
        node["file"].fail("must not be empty");
    }
    std::string gridName = node.has("name") ? node["name"].string() : std::string();
    std::uint32_t resolution = node.has("resolution") ? node["resolution"].integer(1, kDensityResolutionMax) : 256u;
    std::string path = name[0] == '/' ? name : files.folder + name;
    DensityGrid grid;
    try {
        grid = decodeVdbDensity(files.read(path, "density grid"), path, gridName, resolution);
    } catch (const InputError& e) {
        node["file"].fail(e.what());
    }
    if (node.has("min") != node.has("max")) {
        node.fail("min and max come together");
    }
    if (node.has("min")) {
        grid.lower = node["min"].vec3();
        grid.upper = node["max"].vec3();
        if (!(grid.lower.x < grid.upper.x && grid.lower.y < grid.upper.y && grid.lower.z < grid.upper.z)) {
            node["max"].fail("must exceed min in x, y and z");
        }
    }
    return grid;
}

Medium readMedium(Scene& scene, const JsonNode& node, const MediaFiles& files) {
    node.allowKeys({"absorption", "scattering", "density", "albedo", "g", "grid"});
    Medium md = homogeneousMedium();
    bool coefficients = node.has("absorption") || node.has("scattering");
    if (coefficients && (node.has("density") || node.has("albedo"))) {
        node.fail("give absorption and scattering, or density and albedo, not both");
    }
    if (coefficients) {
        md.absorption = node.has("absorption") ? coefficient(node["absorption"]) : glm::vec3(0.0f);
        md.scattering = node.has("scattering") ? coefficient(node["scattering"]) : glm::vec3(0.0f);
    } else {
        // σt = density, σs = albedo·σt, σa = (1 − albedo)·σt.
        glm::vec3 density = coefficient(node["density"]);
        glm::vec3 albedo = node.has("albedo") ? node["albedo"].rgb(kUnit) : glm::vec3(1.0f);
        md.scattering = albedo * density;
        md.absorption = (glm::vec3(1.0f) - albedo) * density;
    }
    if (!std::isfinite(md.absorption.x + md.absorption.y + md.absorption.z + md.scattering.x + md.scattering.y +
                       md.scattering.z)) {
        node.fail("the coefficients overflow a float");
    }
    // g = ±1 is a delta: no longer a phase function Henyey–Greenstein can sample.
    md.g = node.has("g") ? node["g"].number({-0.99, 0.99, false, false}) : 0.0f;
    if (node.has("grid")) {
        DensityGrid grid = readDensityGrid(node["grid"], files);
        try {
            md.grid = scene.addDensityGrid(grid);
        } catch (const InputError& e) {
            node["grid"].fail(e.what());
        }
        md.resolution = grid.resolution;
        md.lower = grid.lower;
        md.upper = grid.upper;
    }
    return md;
}

const Medium& namedMedium(const JsonNode& name, const MediaByName& media) {
    auto found = media.find(name.string());
    if (found == media.end()) {
        std::string names;
        for (const auto& [n, md] : media) {
            names += (names.empty() ? "" : ", ") + n;
        }
        name.fail("unknown medium '" + name.string() + "' (the scene's \"media\" name " +
                  (names.empty() ? std::string("none") : names) + ")");
    }
    return found->second;
}

}  // namespace

MediaByName readMedia(Scene& scene, const JsonNode& node, const MediaFiles& files) {
    MediaByName media;
    for (const auto& [name, medium] : node.members()) {
        media[name] = readMedium(scene, medium, files);
    }
    return media;
}

std::uint32_t readMaterialMedium(Scene& scene, const JsonNode& node, const MediaByName& media) {
    return scene.addMedium(namedMedium(node, media));
}

void readSceneMedium(Scene& scene, const JsonNode& node, const MediaByName& media) {
    if (node.value().is_string()) {
        scene.fillWithMedium(scene.addMedium(namedMedium(node, media)));
        return;
    }
    node.allowKeys({"name", "min", "max"});
    Medium md = namedMedium(node["name"], media);
    if (node.has("min") != node.has("max")) {
        node.fail("min and max come together");
    }
    if (node.has("min") && md.grid != NONE) {
        node.fail("medium '" + node["name"].string() + "' fills its grid's box: place the grid with its own min and max");
    }
    if (node.has("min")) {
        md.lower = node["min"].vec3();
        md.upper = node["max"].vec3();
        if (!(md.lower.x < md.upper.x && md.lower.y < md.upper.y && md.lower.z < md.upper.z)) {
            node["max"].fail("must exceed min in x, y and z");
        }
    }
    scene.fillWithMedium(scene.addMedium(md));
}

}  // namespace photon
