// Moving lights: the scene as loaded, plus an offset per light, applied by Scene::moveLight (which
// moves what belongs to a light with it: an area light's visible surface, the emissive
// triangles; a directional light turns instead), and the background's radiance. Offsets are
// applied to the loaded scene, never accumulated into a moved copy, so nothing drifts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/scene.h"

namespace photon::viewer {

class LightEditor {
public:
    LightEditor() = default;
    explicit LightEditor(Scene loaded);

    std::uint32_t lightCount() const { return std::uint32_t(loaded_.lights.size()); }
    // "point 0", "sphere 2", "directional 3", ... for the HUD.
    std::string lightName(std::uint32_t light) const;
    // Where the light is now (Scene::lightHandle: a quad light's corner, a directional light's
    // point on its side of the scene).
    glm::vec3 position(std::uint32_t light) const;
    void setPosition(std::uint32_t light, glm::vec3 position);
    void move(std::uint32_t light, glm::vec3 delta) { setPosition(light, position(light) + delta); }
    // The radiance of rays that leave the scene (its infinite light, LIGHT_ENVIRONMENT).
    glm::vec3 background() const { return background_; }
    void setBackground(glm::vec3 radiance) { background_ = radiance; }
    void reset();

    // The loaded scene with every light moved, finalized again (bounds and light sampling).
    Scene scene() const;
    const Scene& loaded() const { return loaded_; }

private:
    Scene loaded_;
    std::vector<glm::vec3> offsets_;
    glm::vec3 background_{0.0f};
};

}  // namespace photon::viewer
