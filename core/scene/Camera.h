// Pinhole camera (CONVENTIONS.md): forward = normalize(target - position),
// right = normalize(cross(forward, up)), true up = cross(right, forward).
#pragma once

#include "base/Bounds.h"

#include <glm/glm.hpp>
#include <shared/GpuTypes.h>
#include <vector>

namespace bl {

enum class FovAxis { X, Y };

struct CameraPose {
    glm::vec3 position{0.0f, 0.0f, 1.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
};

struct CameraKeyframe {
    double time = 0.0;
    CameraPose pose;
};

struct Camera {
    CameraPose pose;
    float fovDegrees = 45.0f;
    FovAxis fovAxis = FovAxis::X;
    glm::ivec2 resolution{512, 512};
    std::vector<CameraKeyframe> keys; // empty: static

    bool animated() const { return !keys.empty(); }
    CameraPose poseAt(double time) const;
};

// The camera as the shaders and the reference tracer see it. `nearPlane` (world units) clips
// geometry closer than that; viewProj uses reversed infinite depth (near -> 1, infinity -> 0), which
// keeps depth precision the same at every scene scale.
shader::GpuCamera makeGpuCamera(const Camera& camera, double time, float nearPlane);

// A camera on the +z side of the bounds, looking along -z, whose view cone contains their sphere.
Camera fitCamera(const Bounds& bounds, glm::ivec2 resolution);

} // namespace bl
