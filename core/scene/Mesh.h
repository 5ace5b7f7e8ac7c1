// A triangle mesh with one material and one emission, in the scene's world units. Loaders split
// files by material so that every draw has a single material.
#pragma once

#include "scene/Animation.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace bl {

struct Mesh {
    std::string name;       // "<file>:<group or material>"
    std::string sourceFile; // where it came from, for messages
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals; // per vertex, unit; filled by cleanup when the file has none
    std::vector<glm::vec2> uvs;     // per vertex, or empty
    std::vector<glm::uvec3> triangles;
    std::uint32_t material = 0;
    glm::vec3 emission{0.0f}; // radiance from the front (counter-clockwise) face
    RigidAnimation animation; // applied on top of the (baked) static transform

    bool emissive() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }
};

} // namespace bl
