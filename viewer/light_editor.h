// Moving lights: the scene as loaded, plus an offset per light. An area light's visible surface
// (the emitter sphere or quad that Scene::addSphereLight/addQuadLight made for it) moves with it.
// Offsets are applied to the loaded scene, never accumulated into a moved copy, so nothing drifts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace photon::viewer {

class LightEditor {
public:
    LightEditor() = default;
    explicit LightEditor(Scene loaded);

    std::uint32_t lightCount() const { return std::uint32_t(loaded_.lights.size()); }
    // "point 0", "sphere 2", ... for the HUD.
    std::string lightName(std::uint32_t light) const;
    // Where the light is now (a quad light: its corner).
    glm::vec3 position(std::uint32_t light) const;
    void setPosition(std::uint32_t light, glm::vec3 position);
    void move(std::uint32_t light, glm::vec3 delta) { setPosition(light, position(light) + delta); }
    void reset();

    // The loaded scene with every light moved, finalized again (bounds and light sampling).
    Scene scene() const;
    const Scene& loaded() const { return loaded_; }

private:
    Scene loaded_;
    std::vector<glm::vec3> offsets_;
};

}  // namespace photon::viewer
