// Mode bidir's environment light by bundles ([TO12] section 3, Eq. 2; `environment_bundles`): per
// frame E extra bundles in the pool, along directions drawn by the environment's importance
// q (core/bundle/DirectionSampler, Importance: Eq. 2 with the offset L_o), each with the
// environment's radiance both ways and p_r = q(d) + q(-d) for the evaluation pass
// (shaders/modes/bidir/EnvironmentDirect.glsl), which adds their direct light to layer `direct`.
// Only direct environment light: indirect light from the environment (env -> y -> x) is not
// bidir's (the plan says so).
#pragma once

#include "bundle/BundleFrame.h"
#include "bundle/DirectionSampler.h"
#include "sampling/EnvironmentLight.h"
#include "scene/Scene.h"
#include "vk/Buffer.h"

#include <memory>
#include <vector>

namespace bl {

class EnvironmentBundles {
public:
    // `count`: E bundles per frame (0 or no environment: none, and the block says so).
    EnvironmentBundles(const vk::Context& ctx, const Scene& scene, std::uint32_t count, float offset);

    std::uint32_t count() const { return mCount; }
    // Frame `frame`'s E bundle frames (slots firstSlot .. firstSlot + E - 1 of the pool) for run
    // seed `seed`, fitted as the pairs' bundles are (`points` empty: the scene's sphere); fills the
    // block. Directions are a pure function of (seed, frame, e).
    std::vector<shader::BundleFrame> frames(std::uint32_t frame, std::uint32_t seed, std::uint32_t firstSlot,
                                            const std::vector<glm::vec3>& points, const Bounds& bounds,
                                            std::uint32_t resolution);
    VkBuffer buffer() const { return mBuffer.get(); }

private:
    std::uint32_t mCount = 0;
    float mOffset = 0.1f;
    std::unique_ptr<EnvironmentLight> mEnvironment;
    std::unique_ptr<DirectionSampler> mDirections;
    vk::Buffer mBuffer; // BidirEnvironmentHeader + BidirEnvironmentBundle[E] (Upload)
};

} // namespace bl
