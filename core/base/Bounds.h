// Axis-aligned bounding box.
#pragma once

#include <glm/glm.hpp>
#include <limits>

namespace bl {

struct Bounds {
    glm::vec3 lo{std::numeric_limits<float>::max()};
    glm::vec3 hi{std::numeric_limits<float>::lowest()};

    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    void extend(const glm::vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void extend(const Bounds& b) {
        if (!b.empty()) {
            extend(b.lo);
            extend(b.hi);
        }
    }
    glm::vec3 center() const { return 0.5f * (lo + hi); }
    glm::vec3 extent() const { return empty() ? glm::vec3(0.0f) : hi - lo; }
    // Radius of the sphere about center() that contains the box.
    float radius() const { return 0.5f * glm::length(extent()); }
};

} // namespace bl
