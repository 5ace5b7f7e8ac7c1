// Keyframed rigid transforms (time in seconds): linear translation, spherical rotation.
#pragma once

#include "base/Bounds.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <vector>

namespace bl {

struct RigidKeyframe {
    double time = 0.0;
    glm::vec3 translate{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
};

class RigidAnimation {
public:
    // Keys must have strictly increasing times (the loader checks).
    void addKey(const RigidKeyframe& key) { mKeys.push_back(key); }
    bool animated() const { return !mKeys.empty(); }
    const std::vector<RigidKeyframe>& keys() const { return mKeys; }
    // Transform at time t; clamps outside the keyed range; identity when not animated.
    glm::mat4 at(double t) const;
    // A box containing `local` (a box in the animated object's own space) at every time, including
    // the arcs rotations sweep between keys; `local` itself when not animated.
    Bounds sweptBounds(const Bounds& local) const;

private:
    std::vector<RigidKeyframe> mKeys;
};

// Rotation from Euler angles in degrees, applied about x, then y, then z.
glm::quat rotationFromEulerDegrees(const glm::vec3& degrees);

} // namespace bl
