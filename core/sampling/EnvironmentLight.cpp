#include "sampling/EnvironmentLight.h"

#include "image/BilinearLookup.h"

#include <algorithm>
#include <cmath>
#include <shared/EnvMap.h>
#include <shared/Sampling.h>

namespace bl {

namespace {
constexpr float kPi = shader::kPi;
} // namespace

EnvironmentLight::EnvironmentLight(const Environment& env, bool importance)
    : mPresent(env.present), mMap(env.hasMap() ? &env.map : nullptr), mConstant(env.radiance),
      mScale(env.scale), mRotation(glm::radians(env.rotationDegrees)) {
    if (!mMap || !importance) {
        return;
    }
    const int w = mMap->width(), h = mMap->height();
    // Texel weight: the largest luminance among the 3x3 texels its bilinear footprint touches
    // (so the density is positive wherever the filtered radiance is), times sin(theta) for the
    // lat-long area.
    std::vector<float> weights(static_cast<std::size_t>(w) * h);
    for (int y = 0; y < h; ++y) {
        float sinTheta = std::sin(kPi * (y + 0.5f) / h);
        for (int x = 0; x < w; ++x) {
            float m = 0.0f;
            for (int dy = -1; dy <= 1; ++dy) {
                int yy = std::clamp(y + dy, 0, h - 1);
                for (int dx = -1; dx <= 1; ++dx) {
                    int xx = (x + dx + w) % w;
                    m = std::max(m, shader::blLuminance(mMap->at(xx, yy)));
                }
            }
            weights[static_cast<std::size_t>(y) * w + x] = m * sinTheta;
        }
    }
    mDistribution = Distribution2D(weights, w, h);
}

glm::vec3 EnvironmentLight::radiance(const glm::vec3& direction) const {
    if (!mPresent) {
        return glm::vec3(0.0f);
    }
    if (!mMap) {
        return mConstant * mScale;
    }
    glm::vec2 uv = shader::blEnvDirectionToUv(direction, mRotation);
    // Longitude wraps around; latitude stops at the poles (the GPU sampler's modes).
    return bilinearLookup(*mMap, uv, Wrap::Repeat, Wrap::Clamp) * mScale;
}

glm::vec3 EnvironmentLight::sample(glm::vec2 u, float* pdf) const {
    if (mDistribution.empty()) {
        *pdf = 1.0f / (4.0f * kPi);
        return shader::blSampleUniformSphere(u);
    }
    float density = 0.0f;
    glm::vec2 uv = mDistribution.sample(u, &density);
    float sinTheta = std::sin(kPi * uv.y);
    *pdf = sinTheta > 0.0f ? density / (2.0f * kPi * kPi * sinTheta) : 0.0f;
    return shader::blEnvUvToDirection(uv, mRotation);
}

float EnvironmentLight::pdf(const glm::vec3& direction) const {
    if (mDistribution.empty()) {
        return 1.0f / (4.0f * kPi);
    }
    glm::vec2 uv = shader::blEnvDirectionToUv(direction, mRotation);
    float sinTheta = std::sin(kPi * uv.y);
    return sinTheta > 0.0f ? mDistribution.density(uv) / (2.0f * kPi * kPi * sinTheta) : 0.0f;
}

} // namespace bl
