// Moving lights: the scene as loaded, plus an offset per light, applied by Scene::moveLight (which
// moves what belongs to a light with it: an area light's visible surface, the emissive
// triangles; a directional light turns instead), and the environment's radiance (a colour for a
// uniform one, an intensity for a map) and its turn about the vertical; and each participating
// medium's density (a factor on its coefficients) and Henyey–Greenstein g. Offsets and factors
// are applied to the loaded scene, never accumulated into a changed copy, so nothing drifts.
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
    // The environment (what rays that leave the scene see, LIGHT_ENVIRONMENT): a map, or uniform.
    bool environmentIsMap() const { return !loaded_.environment.map.empty(); }
    // A uniform environment's radiance, or the factor on a map's texels.
    glm::vec3 environmentRadiance() const { return environmentRadiance_; }
    void setEnvironmentRadiance(glm::vec3 radiance) { environmentRadiance_ = radiance; }
    // Degrees the environment is turned about +Y, on top of the scene's own rotation.
    float environmentTurn() const { return environmentTurn_; }
    void setEnvironmentTurn(float degrees) { environmentTurn_ = degrees; }
    // The scene's participating media: a factor on each one's coefficients (its density), and its g.
    std::uint32_t mediumCount() const { return std::uint32_t(loaded_.media.size()); }
    std::string mediumName(std::uint32_t medium) const;
    float mediumDensity(std::uint32_t medium) const { return mediumDensity_[medium]; }
    void setMediumDensity(std::uint32_t medium, float factor) { mediumDensity_[medium] = factor; }
    float mediumG(std::uint32_t medium) const { return mediumG_[medium]; }
    void setMediumG(std::uint32_t medium, float g) { mediumG_[medium] = g; }
    void reset();

    // The loaded scene with every light moved, finalized again (bounds and light sampling).
    Scene scene() const;
    const Scene& loaded() const { return loaded_; }

private:
    Scene loaded_;
    std::vector<glm::vec3> offsets_;
    glm::vec3 environmentRadiance_{0.0f};
    float environmentTurn_ = 0.0f;
    std::vector<float> mediumDensity_;
    std::vector<float> mediumG_;
};

}  // namespace photon::viewer
