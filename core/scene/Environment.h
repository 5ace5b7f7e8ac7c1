// Radiance arriving from infinity: a lat-long map (CONVENTIONS.md) or a constant.
#pragma once

#include "image/Image.h"

#include <glm/glm.hpp>
#include <string>

namespace bl {

struct Environment {
    bool present = false;
    std::string file;          // empty: constant radiance
    Image map;                 // lat-long, linear radiance (before `scale`)
    glm::vec3 radiance{0.0f};  // constant environment when there is no map
    float scale = 1.0f;
    float rotationDegrees = 0.0f; // about +y

    bool hasMap() const { return present && !map.empty(); }
};

} // namespace bl
