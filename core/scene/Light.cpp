#include "scene/Light.h"

#include <algorithm>

namespace bl {

Light Light::at(double time) const {
    Light out = *this;
    if (keys.empty()) {
        return out;
    }
    if (time <= keys.front().time) {
        out.position = keys.front().position;
        out.direction = keys.front().direction;
        return out;
    }
    if (time >= keys.back().time) {
        out.position = keys.back().position;
        out.direction = keys.back().direction;
        return out;
    }
    auto next = std::upper_bound(keys.begin(), keys.end(), time,
                                 [](double t, const LightKeyframe& key) { return t < key.time; });
    const LightKeyframe& a = *(next - 1);
    const LightKeyframe& b = *next;
    const float s = static_cast<float>((time - a.time) / (b.time - a.time));
    out.position = glm::mix(a.position, b.position, s);
    const glm::vec3 blend = glm::mix(a.direction, b.direction, s);
    // Opposite key directions cancel halfway: no direction is nearer than the other, keep a's.
    const float length = glm::length(blend);
    out.direction = length > 0.0f ? blend / length : a.direction;
    return out;
}

} // namespace bl
