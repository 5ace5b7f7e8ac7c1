#include "reference/SphericalTriangle.h"

#include <algorithm>
#include <cmath>

namespace bl {

namespace {
constexpr float kPi = 3.14159265358979323846f;

float safeSqrt(float x) { return std::sqrt(std::max(0.0f, x)); }

// Angle between unit vectors without the precision loss of acos near 0 and pi.
float angleBetween(const glm::vec3& v1, const glm::vec3& v2) {
    if (glm::dot(v1, v2) < 0.0f) {
        return kPi - 2.0f * std::asin(std::clamp(glm::length(v1 + v2) / 2.0f, -1.0f, 1.0f));
    }
    return 2.0f * std::asin(std::clamp(glm::length(v2 - v1) / 2.0f, -1.0f, 1.0f));
}

glm::vec3 gramSchmidt(const glm::vec3& v, const glm::vec3& w) { return v - glm::dot(v, w) * w; }
} // namespace

float triangleSolidAngle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    glm::vec3 x = glm::normalize(a - p), y = glm::normalize(b - p), z = glm::normalize(c - p);
    float numerator = std::abs(glm::dot(x, glm::cross(y, z)));
    float denominator = 1.0f + glm::dot(x, y) + glm::dot(y, z) + glm::dot(z, x);
    return std::abs(2.0f * std::atan2(numerator, denominator));
}

bool sampleSphericalTriangle(const glm::vec3& p, const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2,
                             glm::vec2 u, glm::vec3& direction) {
    glm::vec3 a = glm::normalize(v0 - p), b = glm::normalize(v1 - p), c = glm::normalize(v2 - p);
    glm::vec3 nab = glm::cross(a, b), nbc = glm::cross(b, c), nca = glm::cross(c, a);
    if (glm::dot(nab, nab) == 0.0f || glm::dot(nbc, nbc) == 0.0f || glm::dot(nca, nca) == 0.0f) {
        return false;
    }
    nab = glm::normalize(nab);
    nbc = glm::normalize(nbc);
    nca = glm::normalize(nca);
    const float alpha = angleBetween(nab, -nca);
    const float beta = angleBetween(nbc, -nab);
    const float gamma = angleBetween(nca, -nbc);
    // Sample the sub-triangle's area A' uniformly in [0, A], via its angle sum A' + pi.
    const float areaPi = alpha + beta + gamma;
    const float sampledPi = kPi + u.x * (areaPi - kPi);
    const float cosAlpha = std::cos(alpha), sinAlpha = std::sin(alpha);
    const float sinPhi = std::sin(sampledPi) * cosAlpha - std::cos(sampledPi) * sinAlpha;
    const float cosPhi = std::cos(sampledPi) * cosAlpha + std::sin(sampledPi) * sinAlpha;
    const float k1 = cosPhi + cosAlpha;
    const float k2 = sinPhi - sinAlpha * glm::dot(a, b);
    const float denominator = (k2 * sinPhi + k1 * cosPhi) * sinAlpha;
    float cosBp = denominator != 0.0f ? (k2 + (k2 * cosPhi - k1 * sinPhi) * cosAlpha) / denominator : 1.0f;
    cosBp = std::clamp(cosBp, -1.0f, 1.0f);
    const float sinBp = safeSqrt(1.0f - cosBp * cosBp);
    glm::vec3 ca = gramSchmidt(c, a);
    if (glm::dot(ca, ca) == 0.0f) {
        return false;
    }
    glm::vec3 cp = cosBp * a + sinBp * glm::normalize(ca);
    // Then a point on the arc from b to c' with the right density.
    const float cosTheta = 1.0f - u.y * (1.0f - glm::dot(cp, b));
    const float sinTheta = safeSqrt(1.0f - cosTheta * cosTheta);
    glm::vec3 cpb = gramSchmidt(cp, b);
    if (glm::dot(cpb, cpb) == 0.0f) {
        direction = b;
        return true;
    }
    direction = glm::normalize(cosTheta * b + sinTheta * glm::normalize(cpb));
    return std::isfinite(direction.x) && std::isfinite(direction.y) && std::isfinite(direction.z);
}

} // namespace bl
