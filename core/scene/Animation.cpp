#include "scene/Animation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace bl {
namespace {

// Largest rotation (radians) between two times whose boxes are joined in sweptBounds. A point at
// distance r from the rotation axis leaves the straight line between its two ends by at most
// r * step^2 / 8 (linear interpolation error); 5 degrees keeps that below 0.1% of r.
constexpr double kMaxSweepStepRadians = 5.0 * 3.14159265358979323846 / 180.0;

std::array<glm::vec3, 8> corners(const Bounds& b) {
    std::array<glm::vec3, 8> out;
    for (int c = 0; c < 8; ++c) {
        out[c] = glm::vec3((c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z);
    }
    return out;
}

} // namespace

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

Bounds RigidAnimation::sweptBounds(const Bounds& local) const {
    if (mKeys.empty() || local.empty()) {
        return local;
    }
    const std::array<glm::vec3, 8> points = corners(local);
    float reach = 0.0f; // largest distance of the box from the rotation centre (the origin)
    for (const glm::vec3& p : points) {
        reach = std::max(reach, glm::length(p));
    }
    auto extendAt = [&](Bounds& b, double t) {
        const glm::mat4 m = at(t);
        for (const glm::vec3& p : points) {
            b.extend(glm::vec3(m * glm::vec4(p, 1.0f)));
        }
    };
    Bounds out;
    extendAt(out, mKeys.front().time); // also the pose before the first key and after the last
    for (std::size_t i = 0; i + 1 < mKeys.size(); ++i) {
        const RigidKeyframe& a = mKeys[i];
        const RigidKeyframe& b = mKeys[i + 1];
        // slerp takes the shorter way, so the angle comes from |cos(half angle)|.
        const double cosHalf = std::min(1.0, std::abs(double(glm::dot(a.rotation, b.rotation))));
        const double angle = 2.0 * std::acos(cosHalf);
        const int steps = std::max(1, static_cast<int>(std::ceil(angle / kMaxSweepStepRadians)));
        const double step = angle / steps;
        // Translation is linear in time, so only the rotation bends a point's path off the line
        // between its positions at the two ends of a step.
        const float bulge = static_cast<float>(reach * step * step / 8.0);
        for (int j = 0; j < steps; ++j) {
            Bounds piece;
            extendAt(piece, a.time + (b.time - a.time) * j / steps);
            extendAt(piece, a.time + (b.time - a.time) * (j + 1) / steps);
            piece.lo -= glm::vec3(bulge);
            piece.hi += glm::vec3(bulge);
            out.extend(piece);
        }
    }
    return out;
}

glm::quat rotationFromEulerDegrees(const glm::vec3& degrees) {
    glm::vec3 r = glm::radians(degrees);
    glm::quat qx = glm::angleAxis(r.x, glm::vec3(1, 0, 0));
    glm::quat qy = glm::angleAxis(r.y, glm::vec3(0, 1, 0));
    glm::quat qz = glm::angleAxis(r.z, glm::vec3(0, 0, 1));
    return qz * qy * qx;
}

} // namespace bl
