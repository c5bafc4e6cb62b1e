// The environment on the host: what a scene's environment light is made of (a map read from a
// file, a sky computed from a daylight model, the studio environment of model files, or one
// uniform radiance), and the sampling distribution built from it for shared/environment.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace photon {

// An equirectangular map of linear RGB radiance [W·sr⁻¹·m⁻²], row by row from the zenith (row 0)
// to the nadir, in shared/environment.h's conventions (+Y up, the centre column along −Z).
struct EnvironmentMap {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<glm::vec3> texels;  // width × height, finite and ≥ 0

    bool empty() const { return height == 0; }
};

// The largest map accepted, in texels along each edge.
inline constexpr std::uint32_t kEnvironmentWidthMax = 16384;
inline constexpr std::uint32_t kEnvironmentHeightMax = 8192;

// A scene's environment: what rays that leave the scene see, and, if it `lights`, a light that
// emits photons and is sampled by shadow rays. Its radiance in a direction is `radiance` (uniform)
// or `radiance` times the map's texel there; the map is turned by `rotation`.
struct EnvironmentLight {
    std::string source;                // where the map came from, for people: a file, "sky", "studio"; "" uniform
    EnvironmentMap map;                // empty: uniform
    glm::vec3 radiance{0.0f};          // the uniform radiance, or the factor on the map's texels (intensity)
    glm::mat3 rotation{1.0f};          // world direction = rotation · map direction
    bool lights = false;               // a `background` only colours what the camera sees
};

// The sampling distribution of a map (shared/environment.h): its RGBE texels, the marginal and
// conditional cdfs of luminance × sin θ, and ∫ texel dω over the sphere (per channel) for its power.
struct EnvironmentDistribution {
    std::vector<std::uint32_t> texels;
    std::vector<float> cdf;
    glm::dvec3 integral{0.0};
};

// Radiance's shared-exponent encoding of a non-negative finite colour (shared/environment.h
// decodes it).
std::uint32_t encodeRgbe(glm::vec3 c);

// Builds the distribution on all threads. A map whose luminance is 0 everywhere gets uniform cdfs
// (and an integral of 0: it emits nothing).
EnvironmentDistribution buildEnvironmentDistribution(const EnvironmentMap& map);

// The rotation by `degrees` about `axis` (the scene format's "rotate").
glm::mat3 environmentRotation(float degrees, glm::vec3 axis);

}  // namespace photon
