#include "light_editor.h"

#include <algorithm>
#include <utility>

namespace photon::viewer {

LightEditor::LightEditor(Scene loaded)
    : loaded_(std::move(loaded)), offsets_(loaded_.lights.size(), glm::vec3(0.0f)), environmentRadiance_(loaded_.environment.radiance) {
    reset();
}

std::string LightEditor::mediumName(std::uint32_t medium) const {
    std::string name = "medium " + std::to_string(medium);
    if (medium == loaded_.medium) {
        name += " (fills the scene)";
    }
    if (loaded_.media[medium].grid != NONE) {
        name += ", a grid";
    }
    return name;
}

std::string LightEditor::lightName(std::uint32_t light) const {
    return std::string(lightTypeName(loaded_.lights[light].type)) + " " + std::to_string(light);
}

glm::vec3 LightEditor::position(std::uint32_t light) const { return loaded_.lightHandle(light) + offsets_[light]; }

void LightEditor::setPosition(std::uint32_t light, glm::vec3 position) {
    offsets_[light] = position - loaded_.lightHandle(light);
}

void LightEditor::reset() {
    std::fill(offsets_.begin(), offsets_.end(), glm::vec3(0.0f));
    environmentRadiance_ = loaded_.environment.radiance;
    environmentTurn_ = 0.0f;
    mediumDensity_.assign(loaded_.media.size(), 1.0f);
    mediumG_.clear();
    for (const Medium& md : loaded_.media) {
        mediumG_.push_back(md.g);
    }
}

Scene LightEditor::scene() const {
    Scene s = loaded_;
    for (std::uint32_t l = 0; l < s.lights.size(); ++l) {
        s.moveLight(l, offsets_[l]);
    }
    s.environment.radiance = environmentRadiance_;
    s.environment.rotation = environmentRotation(environmentTurn_, glm::vec3(0.0f, 1.0f, 0.0f)) * loaded_.environment.rotation;
    for (std::uint32_t m = 0; m < s.media.size(); ++m) {
        s.media[m].absorption *= mediumDensity_[m];
        s.media[m].scattering *= mediumDensity_[m];
        s.media[m].g = mediumG_[m];
    }
    s.finalize();
    return s;
}

}  // namespace photon::viewer
