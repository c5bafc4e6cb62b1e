#include "core/scene/studio_environment.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/system/parallel.h"

namespace photon {
namespace {

constexpr double kPi = 3.14159265358979323846;

double radians(double degrees) { return degrees * kPi / 180.0; }

// The map direction at elevation `elevation` and azimuth `phi` (degrees), as equirectDirection
// writes it with θ = 90° − elevation.
glm::dvec3 direction(double elevation, double phi) {
    double e = radians(elevation);
    double p = radians(phi);
    return {std::cos(e) * std::sin(p), std::sin(e), -std::cos(e) * std::cos(p)};
}

// A rectangle facing the origin: a direction d hits it at (d·right, d·up) / (d·centre) in its
// plane at unit distance, inside if within (halfWidth, halfHeight) there.
struct SoftBox {
    glm::dvec3 centre, right, up;
    double halfWidth, halfHeight;  // tangents of the half angles
    double weight;                 // relative radiance

    SoftBox(double elevation, double phi, double wideDegrees, double highDegrees, double relative)
        : centre(direction(elevation, phi)),
          right(glm::normalize(glm::cross(glm::dvec3(0.0, 1.0, 0.0), centre))),
          up(glm::cross(centre, right)),
          halfWidth(std::tan(radians(0.5 * wideDegrees))),
          halfHeight(std::tan(radians(0.5 * highDegrees))),
          weight(relative) {}

    double radiance(glm::dvec3 d) const {
        double z = glm::dot(d, centre);
        if (z <= 0.0) {
            return 0.0;
        }
        return weight * edge(glm::dot(d, right) / z, halfWidth) * edge(glm::dot(d, up) / z, halfHeight);
    }

    // 1 inside, 0 outside, a smoothstep over ±kFeather around the edge at `half`.
    static double edge(double t, double half) {
        constexpr double kFeather = 0.1;
        double s = std::clamp((half + kFeather - std::abs(t)) / (2.0 * kFeather), 0.0, 1.0);
        return s * s * (3.0 - 2.0 * s);
    }
};

// The backdrop at height y = cos θ: 0.5 + 0.3 y above, 0.15 below, blended over ±2°.
double backdrop(double y) {
    double blend = std::clamp((y + std::sin(radians(2.0))) / (2.0 * std::sin(radians(2.0))), 0.0, 1.0);
    blend = blend * blend * (3.0 - 2.0 * blend);
    return 0.15 + (0.5 + 0.3 * std::max(y, 0.0) - 0.15) * blend;
}

}  // namespace

EnvironmentMap makeStudioMap(std::uint32_t width, std::uint32_t height) {
    if (width < 1 || height < 1 || width > kEnvironmentWidthMax || height > kEnvironmentHeightMax) {
        throw std::logic_error("makeStudioMap: a map of " + std::to_string(width) + " × " + std::to_string(height) +
                               " texels");
    }
    const SoftBox boxes[] = {
        {45.0, -135.0, 60.0, 40.0, 1.0},  // key
        {20.0, 120.0, 50.0, 35.0, 0.35},  // fill
        {45.0, 20.0, 15.0, 40.0, 0.6},    // rim
    };
    EnvironmentMap map;
    map.width = width;
    map.height = height;
    std::size_t w = width;
    std::size_t h = height;
    map.texels.resize(w * h);
    std::vector<float> boxTexels(w * h);
    double dTheta = kPi / double(h);
    double dPhi = 2.0 * kPi / double(w);

    // Backdrop and boxes (at relative radiance) at texel centres, and each row's share of the
    // up-facing irradiance of both: Σ texel ∫ cos θ dω over the texels above the horizon,
    // ∫ cos θ sin θ dθ dφ = dφ (sin² θ1 − sin² θ0) / 2.
    std::vector<glm::dvec2> rowIrradiance(h, glm::dvec2(0.0));
    parallelFor(h, 4, [&](std::size_t first, std::size_t last) {
        for (std::size_t y = first; y < last; ++y) {
            double theta = dTheta * (double(y) + 0.5);
            glm::dvec2 sum(0.0);
            for (std::size_t x = 0; x < w; ++x) {
                double phi = dPhi * (double(x) + 0.5) - kPi;
                glm::dvec3 d(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
                double box = 0.0;
                for (const SoftBox& b : boxes) {
                    box += b.radiance(d);
                }
                double wall = backdrop(d.y);
                map.texels[y * w + x] = glm::vec3(float(wall));
                boxTexels[y * w + x] = float(box);
                sum += glm::dvec2(float(wall), float(box));
            }
            double theta0 = dTheta * double(y);
            if (theta0 < 0.5 * kPi) {
                double s0 = std::sin(theta0);
                double s1 = std::sin(std::min(theta0 + dTheta, 0.5 * kPi));
                rowIrradiance[y] = sum * (0.5 * dPhi * (s1 * s1 - s0 * s0));
            }
        }
    });
    glm::dvec2 irradiance(0.0);  // of the backdrop, of the boxes at relative radiance
    for (const glm::dvec2& e : rowIrradiance) {
        irradiance += e;
    }
    // The backdrop gives ≈ 0.7π; the boxes make up the rest of π.
    float boxScale = irradiance.y > 0.0 ? float(std::max(0.0, kPi - irradiance.x) / irradiance.y) : 0.0f;
    for (std::size_t i = 0; i < w * h; ++i) {
        map.texels[i] += glm::vec3(boxScale * boxTexels[i]);
    }
    return map;
}

}  // namespace photon
