// The camera side every per-pixel GPU mode shares: one jittered camera sample per pixel and
// iteration, rasterized into the G-buffer, and the layered accumulator its shading adds to. It owns
// set 0 of the mode's shading shader (shaders/gpu/CameraSet.glsl: G-buffer, camera, materials,
// environment, accumulator, and blCameraBackground() for rays that escape); the mode binds its own
// set 1 beside it.
#pragma once

#include "gpu/Accumulator.h"
#include "gpu/GBufferPass.h"
#include "vk/BoundSet.h"

#include <memory>

namespace bl::gpu {

// Where and how iteration k looks at the scene.
struct CameraSample {
    glm::vec2 samplePosition; // sub-pixel position in [0, 1)^2 (PixelSamples.h)
    glm::vec2 jitterNdc;      // the same as an NDC offset, for the rasterizer
    shader::GpuCamera camera; // at the iteration's scene time
    double time = 0.0;
};

class CameraPass {
public:
    // `layers`: the path layers the mode's shader writes (its BL_ACCUM_LAYERS).
    CameraPass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t width, std::uint32_t height,
               std::uint32_t layers);

    // Device memory per pixel (G-buffer and accumulator).
    static VkDeviceSize bytesPerPixel(std::uint32_t layers);

    // Iteration k's sample at scene `time`: the pixel centre without jitter, else k's point of the
    // progressive box filter, shifted by the run's seed (core/sampling/PixelSamples.h).
    CameraSample sample(std::uint32_t k, bool jitter, double time, std::uint64_t seed) const;

    // Records the G-buffer of `s` (its camera is written in the command stream).
    void record(VkCommandBuffer cmd, const CameraSample& s, vk::GpuTimer* timer);

    VkDescriptorSetLayout setLayout() const { return mBound.layout(); }
    VkDescriptorSet set() const { return mBound.set(); }

    const GBufferPass& gbuffer() const { return *mGBuffer; }
    Accumulator& accumulator() { return mAccumulator; }
    const Accumulator& accumulator() const { return mAccumulator; }
    std::uint32_t width() const { return mGBuffer->width(); }
    std::uint32_t height() const { return mGBuffer->height(); }

private:
    const GpuScene* mScene;
    std::unique_ptr<GBufferPass> mGBuffer;
    Accumulator mAccumulator;
    vk::BoundSet mBound;
};

} // namespace bl::gpu
