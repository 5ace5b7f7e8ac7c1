#include "scene/Animation.h"

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

namespace bl {

glm::mat4 RigidAnimation::at(double t) const {
    if (mKeys.empty()) {
        return glm::mat4(1.0f);
    }
    RigidKeyframe k = mKeys.front();
    if (t >= mKeys.back().time) {
        k = mKeys.back();
    } else if (t > mKeys.front().time) {
        auto next = std::upper_bound(mKeys.begin(), mKeys.end(), t,
                                     [](double v, const RigidKeyframe& key) { return v < key.time; });
        const RigidKeyframe& a = *(next - 1);
        const RigidKeyframe& b = *next;
        float s = static_cast<float>((t - a.time) / (b.time - a.time));
        k.translate = glm::mix(a.translate, b.translate, s);
        k.rotation = glm::slerp(a.rotation, b.rotation, s);
    }
    glm::mat4 m = glm::mat4_cast(k.rotation);
    m[3] = glm::vec4(k.translate, 1.0f);
    return m;
}

glm::quat rotationFromEulerDegrees(const glm::vec3& degrees) {
    glm::vec3 r = glm::radians(degrees);
    glm::quat qx = glm::angleAxis(r.x, glm::vec3(1, 0, 0));
    glm::quat qy = glm::angleAxis(r.y, glm::vec3(0, 1, 0));
    glm::quat qz = glm::angleAxis(r.z, glm::vec3(0, 0, 1));
    return qz * qy * qx;
}

} // namespace bl
