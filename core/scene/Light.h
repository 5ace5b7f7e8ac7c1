// Point and spot lights (radiant intensity in W/sr), optionally keyframed: position (and a spot's
// direction) move linearly between keys, like camera keyframes, and hold outside the keyed range.
#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace bl {

struct LightKeyframe {
    double time = 0.0;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0, -1, 0}; // unit; spots only
};

struct Light {
    enum class Type { Point, Spot };
    Type type = Type::Point;
    glm::vec3 position{0.0f};
    glm::vec3 intensity{0.0f};      // W/sr
    glm::vec3 direction{0, -1, 0};  // spot axis (unit)
    float coneAngleDegrees = 30.0f; // spot: half-angle where the intensity reaches zero
    float falloffDegrees = 0.0f;    // spot: width of the smooth edge inside the cone
    std::vector<LightKeyframe> keys; // strictly increasing times; empty: static

    bool animated() const { return !keys.empty(); }
    // The light as it is at `time`: position and direction from the keys (the direction is the
    // normalized linear blend, the earlier key's where the two cancel); itself when static.
    Light at(double time) const;
};

} // namespace bl
