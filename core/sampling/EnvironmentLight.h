// Light from infinity on the CPU (the reference, and bundle direction sampling): radiance lookup (bilinear between texel centres, wrap
// in u, clamp in v, exactly like the GPU sampler) and importance sampling by luminance.
#pragma once

#include "sampling/Distribution.h"
#include "scene/Environment.h"

#include <glm/glm.hpp>

namespace bl {

class EnvironmentLight {
public:
    EnvironmentLight() = default;
    // `importance`: sample by luminance (else uniformly over the sphere).
    EnvironmentLight(const Environment& env, bool importance);

    bool present() const { return mPresent; }
    glm::vec3 radiance(const glm::vec3& direction) const;
    // A direction toward the environment and its solid-angle density.
    glm::vec3 sample(glm::vec2 u, float* pdf) const;
    float pdf(const glm::vec3& direction) const;

private:
    bool mPresent = false;
    const Image* mMap = nullptr;
    glm::vec3 mConstant{0.0f};
    float mScale = 1.0f;
    float mRotation = 0.0f; // radians
    Distribution2D mDistribution;
};

} // namespace bl
