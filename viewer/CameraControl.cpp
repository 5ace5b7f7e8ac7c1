#include "viewer/CameraControl.h"

#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

namespace bl::viewer {

namespace {

constexpr float kRadiansPerPixel = 0.005f;

// `v` turned by `angle` about the unit `axis`.
glm::vec3 turn(const glm::vec3& v, const glm::vec3& axis, float angle) {
    return glm::vec3(glm::rotate(glm::mat4(1.0f), angle, axis) * glm::vec4(v, 0.0f));
}

struct Frame {
    glm::vec3 forward, right, up;
};

Frame frameOf(const CameraPose& p) {
    Frame f;
    f.forward = glm::normalize(p.target - p.position);
    f.right = glm::normalize(glm::cross(f.forward, p.up));
    f.up = glm::cross(f.right, f.forward);
    return f;
}

} // namespace

bool CameraControl::apply(const InputEvent& e, CameraPose& pose) const {
    const Frame f = frameOf(pose);
    const float distance = glm::length(pose.target - pose.position);
    if (e.kind == InputEvent::Kind::Scroll && mStyle == Style::Orbit) {
        const float d = std::max(distance * std::pow(0.9f, float(e.dy)), 1e-4f * mRadius);
        pose.position = pose.target - f.forward * d;
        return e.dy != 0.0;
    }
    if (e.kind != InputEvent::Kind::Drag || (e.dx == 0.0 && e.dy == 0.0)) return false;
    const float yaw = -float(e.dx) * kRadiansPerPixel, pitch = -float(e.dy) * kRadiansPerPixel;
    if (mStyle == Style::Orbit && e.button == 1) {
        const glm::vec3 shift = (-f.right * float(e.dx) + f.up * float(e.dy)) * (distance * 0.002f);
        pose.position += shift;
        pose.target += shift;
        return true;
    }
    // Turn about the pose's up (yaw) and the right axis (pitch), keeping clear of the poles.
    glm::vec3 offset = mStyle == Style::Orbit ? pose.position - pose.target : pose.target - pose.position;
    const float sign = mStyle == Style::Orbit ? 1.0f : -1.0f;
    offset = turn(offset, glm::normalize(pose.up), yaw);
    // Pitch about the axis across the view; a view along `up` has none (no pitch, yaw only).
    const glm::vec3 across = glm::cross(offset, pose.up);
    if (glm::length(across) > 1e-6f * glm::length(offset) * glm::length(pose.up)) {
        const glm::vec3 turned = turn(offset, glm::normalize(across), sign * pitch);
        if (std::abs(glm::dot(glm::normalize(turned), glm::normalize(pose.up))) < 0.995f) offset = turned;
    }
    if (mStyle == Style::Orbit) pose.position = pose.target + offset;
    else pose.target = pose.position + offset;
    return true;
}

bool CameraControl::fly(const Window& window, double seconds, CameraPose& pose) const {
    if (mStyle != Style::Fly) return false;
    const Frame f = frameOf(pose);
    glm::vec3 move(0.0f);
    if (window.held("W")) move += f.forward;
    if (window.held("S")) move -= f.forward;
    if (window.held("D")) move += f.right;
    if (window.held("A")) move -= f.right;
    if (window.held("E")) move += f.up;
    if (window.held("Q")) move -= f.up;
    if (move == glm::vec3(0.0f)) return false;
    // Half the scene's radius per second.
    const glm::vec3 step = glm::normalize(move) * float(0.5 * mRadius * seconds);
    pose.position += step;
    pose.target += step;
    return true;
}

std::string CameraControl::tomlBlock(const Camera& camera, const glm::dvec3& origin) {
    char text[512];
    const glm::dvec3 p = glm::dvec3(camera.pose.position) + origin, t = glm::dvec3(camera.pose.target) + origin;
    std::snprintf(text, sizeof(text),
                  "[camera]\nposition   = [%.9g, %.9g, %.9g]\ntarget     = [%.9g, %.9g, %.9g]\nup         = [%.9g, %.9g, "
                  "%.9g]\nfov        = %.9g\nfov_axis   = \"%s\"\nresolution = [%d, %d]\n",
                  p.x, p.y, p.z, t.x, t.y, t.z, camera.pose.up.x, camera.pose.up.y, camera.pose.up.z,
                  camera.fovDegrees, camera.fovAxis == FovAxis::X ? "x" : "y", camera.resolution.x,
                  camera.resolution.y);
    return text;
}

} // namespace bl::viewer
