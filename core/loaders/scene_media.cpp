#include "core/loaders/scene_media.h"

#include <cmath>

namespace photon {
namespace {

// A coefficient [1/scene unit]: one number for every channel, or an RGB array.
glm::vec3 coefficient(const JsonNode& node) {
    if (node.value().is_number()) {
        return glm::vec3(node.number(kNonNegative));
    }
    return node.rgb(kNonNegative);
}

Medium readMedium(const JsonNode& node) {
    node.allowKeys({"absorption", "scattering", "density", "albedo", "g"});
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

MediaByName readMedia(const JsonNode& node) {
    MediaByName media;
    for (const auto& [name, medium] : node.members()) {
        media[name] = readMedium(medium);
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
