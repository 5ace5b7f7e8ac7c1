#include "scene/MeshTransform.h"

#include <glm/glm.hpp>

namespace bl {

void bakeTransform(Mesh& mesh, const glm::mat4& m) {
    glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
    for (glm::vec3& p : mesh.positions) {
        p = glm::vec3(m * glm::vec4(p, 1.0f));
    }
    for (glm::vec3& n : mesh.normals) {
        n = normalMatrix * n;
    }
}

} // namespace bl
