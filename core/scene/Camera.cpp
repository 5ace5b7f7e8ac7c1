#include "scene/Camera.h"

#include <algorithm>
#include <cmath>

namespace bl {

CameraPose Camera::poseAt(double time) const {
    if (keys.empty()) {
        return pose;
    }
    if (time <= keys.front().time) {
        return keys.front().pose;
    }
    if (time >= keys.back().time) {
        return keys.back().pose;
    }
    auto next = std::upper_bound(keys.begin(), keys.end(), time,
                                 [](double v, const CameraKeyframe& k) { return v < k.time; });
    const CameraKeyframe& a = *(next - 1);
    const CameraKeyframe& b = *next;
    float s = static_cast<float>((time - a.time) / (b.time - a.time));
    return {glm::mix(a.pose.position, b.pose.position, s), glm::mix(a.pose.target, b.pose.target, s),
            glm::normalize(glm::mix(a.pose.up, b.pose.up, s))};
}

shader::GpuCamera makeGpuCamera(const Camera& camera, double time, float nearPlane) {
    CameraPose pose = camera.poseAt(time);
    shader::GpuCamera c{};
    c.position = pose.position;
    c.forward = glm::normalize(pose.target - pose.position);
    c.right = glm::normalize(glm::cross(c.forward, pose.up));
    c.up = glm::cross(c.right, c.forward);
    c.width = static_cast<float>(camera.resolution.x);
    c.height = static_cast<float>(camera.resolution.y);
    const float aspect = c.width / c.height;
    const float t = std::tan(glm::radians(camera.fovDegrees) * 0.5f);
    c.tanHalfX = camera.fovAxis == FovAxis::X ? t : t * aspect;
    c.tanHalfY = camera.fovAxis == FovAxis::Y ? t : t / aspect;

    // clip = (q.x / tanHalfX, -q.y / tanHalfY, near, q.z) for q = camera-space (right, up, forward)
    // coordinates: NDC y points down as Vulkan wants, so image row 0 is the top (Camera.h's rays).
    glm::mat4 m(0.0f);
    auto setRow = [&m](int row, glm::vec3 axis, float offset) {
        m[0][row] = axis.x;
        m[1][row] = axis.y;
        m[2][row] = axis.z;
        m[3][row] = offset;
    };
    setRow(0, c.right / c.tanHalfX, -glm::dot(c.right, c.position) / c.tanHalfX);
    setRow(1, -c.up / c.tanHalfY, glm::dot(c.up, c.position) / c.tanHalfY);
    setRow(2, glm::vec3(0.0f), nearPlane);
    setRow(3, c.forward, -glm::dot(c.forward, c.position));
    c.viewProj = m;
    return c;
}

Camera fitCamera(const Bounds& bounds, glm::ivec2 resolution) {
    Camera cam;
    cam.resolution = resolution;
    cam.fovDegrees = 40.0f;
    cam.fovAxis = FovAxis::Y;
    const float r = std::max(bounds.radius(), 1e-6f);
    const float distance = r / std::sin(glm::radians(cam.fovDegrees) * 0.5f);
    cam.pose.target = bounds.center();
    cam.pose.position = bounds.center() + glm::vec3(0.0f, 0.0f, distance);
    cam.pose.up = glm::vec3(0.0f, 1.0f, 0.0f);
    return cam;
}

} // namespace bl
