// Next-event estimation toward area emitters on the GPU, shared by the modes (issue 21's "first
// shot"): each iteration draws `count` points on the emitters by power (EmitterPointSampler),
// uploads them after a GpuEmitterPointHeader (binding: buffer()) and renders a shadow cube from each (binding: maps(), read by
// shaders/gpu/EmitterPointLight.glsl as the second shadow map). The same machinery as virtual
// point lights, with emitted instead of reflected light.
#pragma once

#include "gpu/EmitterPointSampler.h"
#include "gpu/ShadowCubePass.h"
#include "vk/Buffer.h"

#include <vector>

namespace bl::gpu {

class EmitterPointPass {
public:
    // `count` points per iteration (0: the pass is off and binds 1-element placeholders), shadow
    // cubes of `resolution`^2 texels a face.
    EmitterPointPass(const vk::Context& ctx, const GpuScene& gpuScene, const Scene& scene, std::uint32_t count,
                     std::uint32_t resolution);

    // Device memory the pass needs for `count` cubes of `resolution`^2 (for requireDeviceMemory).
    static VkDeviceSize bytesFor(std::uint32_t count, std::uint32_t resolution);

    // Draws and uploads the points of (run seed, iteration) at scene `time`; call before record().
    void prepare(std::uint64_t seed, std::uint32_t iteration, double time);
    // Renders the prepared points' shadow cubes (timer scope "emitter points").
    void record(VkCommandBuffer cmd, double time, vk::GpuTimer* timer);

    // Points in the buffer: 0 when off or when the scene has no emitters.
    std::uint32_t count() const { return static_cast<std::uint32_t>(mPoints.size()); }
    std::uint32_t resolution() const { return mCubes.resolution(); }
    float inversePower() const { return mSampler.inversePower(); }
    const std::vector<shader::GpuEmitterPoint>& points() const { return mPoints; }
    VkBuffer buffer() const { return mBuffer.get(); }
    const vk::GpuImage& maps() const { return mCubes.maps(); }

private:
    void upload(); // the header and mPoints into the buffer

    EmitterPointSampler mSampler;
    std::uint32_t mRequested;
    float mLift;
    ShadowCubePass mCubes;
    vk::Buffer mBuffer;
    std::vector<shader::GpuEmitterPoint> mPoints;
};

} // namespace bl::gpu
