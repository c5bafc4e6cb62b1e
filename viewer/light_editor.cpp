#include "light_editor.h"

#include <utility>

#include "shared/constants.h"

namespace photon::viewer {

LightEditor::LightEditor(Scene loaded) : loaded_(std::move(loaded)), offsets_(loaded_.lights.size(), glm::vec3(0.0f)) {}

std::string LightEditor::lightName(std::uint32_t light) const {
    const char* kinds[] = {"point", "spot", "sphere", "quad"};
    std::uint32_t type = loaded_.lights[light].type;
    return std::string(type < 4 ? kinds[type] : "light") + " " + std::to_string(light);
}

glm::vec3 LightEditor::position(std::uint32_t light) const { return loaded_.lights[light].position + offsets_[light]; }

void LightEditor::setPosition(std::uint32_t light, glm::vec3 position) {
    offsets_[light] = position - loaded_.lights[light].position;
}

void LightEditor::reset() { std::fill(offsets_.begin(), offsets_.end(), glm::vec3(0.0f)); }

Scene LightEditor::scene() const {
    Scene s = loaded_;
    for (std::uint32_t l = 0; l < s.lights.size(); ++l) {
        glm::vec3 d = offsets_[l];
        s.lights[l].position += d;
        // The emitter surface of an area light carries the material Scene named after the light.
        std::uint32_t emitter = s.findMaterial("light" + std::to_string(l));
        if (emitter == NONE || s.materials[emitter].type != MATERIAL_EMITTER) {
            continue;
        }
        for (Sphere& sphere : s.spheres) {
            if (sphere.material == emitter) {
                sphere.center += d;
            }
        }
        for (Quad& quad : s.quads) {
            if (quad.material == emitter) {
                quad.corner += d;
            }
        }
    }
    s.finalize();
    return s;
}

}  // namespace photon::viewer
