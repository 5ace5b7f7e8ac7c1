// Next-event estimation toward the environment on the GPU, shared by the modes (issue 21's first
// shot for environments; the area emitters' counterpart is gpu/EmitterPointPass.h): each iteration
// draws `count` directions by the environment's importance (DirectionSampler, Importance), uploads
// them after a GpuEnvironmentShadowHeader (binding: buffer()) and renders an orthographic depth map
// along each over the scene's bounding sphere (binding: maps(), an rgba32f 2D array, depth and normal, one layer per
// direction, read by shaders/gpu/EnvironmentShadowLight.glsl). The directions are a stratified
// sequence over the run: iteration i takes the sequence's entries iK .. iK + K - 1.
#pragma once

#include "bundle/DepthMapPass.h"
#include "bundle/DirectionSampler.h"
#include "sampling/EnvironmentLight.h"
#include "scene/Scene.h"
#include "vk/Buffer.h"

#include <shared/EnvironmentShadows.h>

#include <memory>
#include <vector>

namespace bl {

class EnvironmentShadowPass {
public:
    // `count` directions per iteration, depth maps of `resolution`^2 texels; 0 or a scene without
    // an environment: the pass is off (header count 0, one-layer placeholder maps to bind).
    EnvironmentShadowPass(const vk::Context& ctx, const gpu::GpuScene& gpuScene, const Scene& scene, std::uint32_t count,
                          std::uint32_t resolution);

    // Device memory the pass needs (for requireDeviceMemory).
    static VkDeviceSize bytesFor(std::uint32_t count, std::uint32_t resolution);

    // Draws and uploads the directions of (run seed, iteration); call before record().
    void prepare(std::uint64_t seed, std::uint32_t iteration);
    // Renders the prepared directions' depth maps with the scene at `time` (timer scope
    // "environment maps").
    void record(VkCommandBuffer cmd, double time, vk::GpuTimer* timer);

    bool off() const { return mRequested == 0; }
    // Directions in the buffer: those of the last prepare() whose light is not zero.
    std::uint32_t count() const { return static_cast<std::uint32_t>(mShadows.size()); }
    std::uint32_t resolution() const { return mResolution; }
    const std::vector<shader::GpuEnvironmentShadow>& shadows() const { return mShadows; }
    VkBuffer buffer() const { return mBuffer.get(); }
    const vk::GpuImage& maps() const { return mMaps.map(); }

private:
    void upload(); // the header and mShadows into the buffer

    std::uint32_t mRequested;
    std::uint32_t mResolution;
    float mLuminanceScale = 0.0f, mUniformDensity = 0.0f; // q~ (EnvironmentShadows.h)
    Bounds mBounds;
    EnvironmentLight mRadiance;   // L_e, as the modes look it up
    EnvironmentLight mImportance; // luminance-sampled, for the directions
    std::unique_ptr<DirectionSampler> mDirections; // for mSeed
    std::uint32_t mSeed = 0;
    DepthMapPass mMaps;
    vk::Buffer mBuffer;
    std::vector<shader::GpuEnvironmentShadow> mShadows;
};

} // namespace bl
