#include "mesh_shapes.h"

#include <cmath>

namespace photon::tools {
namespace {

constexpr float kPi = 3.14159265358979323846f;

// A grid of (rows + 1) × (columns + 1) vertices made into two triangles a cell, each wound
// counter-clockwise seen from outside when `position` maps (u, v) so that ∂/∂u × ∂/∂v points out.
template <typename Position>
Mesh grid(std::uint32_t rows, std::uint32_t columns, Position position) {
    Mesh mesh;
    mesh.positions.reserve(std::size_t(rows + 1) * (columns + 1));
    mesh.normals.reserve(mesh.positions.capacity());
    for (std::uint32_t i = 0; i <= rows; ++i) {
        for (std::uint32_t j = 0; j <= columns; ++j) {
            glm::vec3 p;
            glm::vec3 n;
            position(float(i) / float(rows), float(j) / float(columns), p, n);
            mesh.positions.push_back(p);
            mesh.normals.push_back(n);
        }
    }
    mesh.triangles.reserve(std::size_t(rows) * columns * 2);
    for (std::uint32_t i = 0; i < rows; ++i) {
        for (std::uint32_t j = 0; j < columns; ++j) {
            std::uint32_t a = i * (columns + 1) + j;
            std::uint32_t b = a + 1;
            std::uint32_t c = a + columns + 1;
            std::uint32_t d = c + 1;
            mesh.triangles.emplace_back(a, c, b);
            mesh.triangles.emplace_back(b, c, d);
        }
    }
    mesh.materials.assign(mesh.triangles.size(), 0u);
    return mesh;
}

}  // namespace

Mesh uvSphere(glm::vec3 centre, float radius, std::uint32_t stacks, std::uint32_t slices, bool smooth) {
    Mesh mesh = grid(stacks, slices, [&](float u, float v, glm::vec3& p, glm::vec3& n) {
        float theta = u * kPi;        // from the north pole
        float phi = v * 2.0f * kPi;   // around
        n = glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
        p = centre + radius * n;
    });
    if (!smooth) {
        mesh.normals.clear();
    }
    return mesh;
}

Mesh bumpySphere(std::uint64_t triangles) {
    auto stacks = std::uint32_t(std::max(2.0, std::sqrt(double(triangles) / 4.0)));
    std::uint32_t slices = 2 * stacks;
    auto height = [](glm::vec3 d) {
        return 1.0f + 0.08f * std::sin(7.0f * d.x + 1.0f) * std::sin(5.0f * d.y + 2.0f) * std::sin(6.0f * d.z) +
               0.03f * std::sin(23.0f * d.x) * std::sin(19.0f * d.y + 1.0f) * std::sin(21.0f * d.z + 2.0f);
    };
    Mesh mesh = grid(stacks, slices, [&](float u, float v, glm::vec3& p, glm::vec3& n) {
        float theta = u * kPi;
        float phi = v * 2.0f * kPi;
        glm::vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
        p = d * height(d);
        n = d;
    });
    // Normals from the surface itself: area-weighted face normals.
    std::vector<glm::vec3> sum(mesh.positions.size(), glm::vec3(0.0f));
    for (glm::uvec3 t : mesh.triangles) {
        glm::vec3 f = glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
        sum[t.x] += f;
        sum[t.y] += f;
        sum[t.z] += f;
    }
    for (std::size_t i = 0; i < sum.size(); ++i) {
        float l = glm::length(sum[i]);
        mesh.normals[i] = l > 0.0f ? sum[i] / l : mesh.normals[i];
    }
    return mesh;
}

Mesh terrain(std::uint64_t triangles) {
    auto side = std::uint32_t(std::max(1.0, std::sqrt(double(triangles) / 2.0)));
    auto h = [](float x, float z) {
        return 0.15f * std::sin(3.0f * x) * std::cos(2.0f * z) + 0.05f * std::sin(11.0f * x + 2.0f * z) +
               0.02f * std::cos(29.0f * z - 5.0f * x);
    };
    return grid(side, side, [&](float u, float v, glm::vec3& p, glm::vec3& n) {
        float x = 2.0f * v - 1.0f;
        float z = 2.0f * u - 1.0f;
        p = glm::vec3(x, h(x, z), z);
        float e = 1e-3f;
        n = glm::normalize(glm::vec3(h(x - e, z) - h(x + e, z), 2.0f * e, h(x, z - e) - h(x, z + e)));
    });
}

}  // namespace photon::tools
