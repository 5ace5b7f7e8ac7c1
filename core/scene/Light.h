// Point and spot lights (radiant intensity in W/sr).
#pragma once

#include "scene/Animation.h"

#include <glm/glm.hpp>

namespace bl {

struct Light {
    enum class Type { Point, Spot };
    Type type = Type::Point;
    glm::vec3 position{0.0f};
    glm::vec3 intensity{0.0f};      // W/sr
    glm::vec3 direction{0, -1, 0};  // spot axis (unit)
    float coneAngleDegrees = 30.0f; // spot: half-angle where the intensity reaches zero
    float falloffDegrees = 0.0f;    // spot: width of the smooth edge inside the cone
};

} // namespace bl
