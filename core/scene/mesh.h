// A triangle mesh as a model file gives it, before it enters a scene (Scene::addMesh): indexed
// vertices with optional normals and texture coordinates, and a scene material per triangle.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace photon {

struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;     // one per vertex, or none
    std::vector<glm::vec4> tangents;  // one per vertex (xyz, w the bitangent sign), or none
    std::vector<glm::vec2> texcoords;   // one per vertex (s right, t down), or none
    std::vector<glm::uvec3> triangles;  // vertex indices, counter-clockwise about the front
    std::vector<std::uint32_t> materials;  // one per triangle
};

// Scale, then rotation, then translation, as one matrix (column vectors): the scene format's
// "transform". `rotateDegrees` turns about `axis` (any length but zero).
glm::mat4 composeTransform(glm::vec3 scale, float rotateDegrees, glm::vec3 axis, glm::vec3 translate);

}  // namespace photon
