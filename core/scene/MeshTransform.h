// A static transform baked into a mesh: positions by the matrix, normals by its inverse transpose.
#pragma once

#include "scene/Mesh.h"

#include <glm/mat4x4.hpp>

namespace bl {

void bakeTransform(Mesh& mesh, const glm::mat4& m);

} // namespace bl
