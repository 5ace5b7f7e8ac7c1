// Omnidirectional shadow maps for every point and spot light: six faces per light, in one r32f
// 2D-array image (layers 6 l .. 6 l + 5), each texel the distance from the light to the nearest
// surface along its centre ray (+inf where nothing). Face bases are CubeFaces.h's, shared with the
// lookups. After record() the image is in VK_IMAGE_LAYOUT_GENERAL for imageLoad.
#pragma once

#include "gpu/GpuScene.h"
#include "vk/GpuTimer.h"
#include "vk/Pipeline.h"

namespace bl::gpu {

class ShadowCubePass {
public:
    ShadowCubePass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t resolution);

    void record(VkCommandBuffer cmd, double time, vk::GpuTimer* timer);

    const vk::GpuImage& maps() const { return mMaps; }
    std::uint32_t resolution() const { return mResolution; }
    std::uint32_t lightCount() const { return mLightCount; }

private:
    const GpuScene* mScene;
    std::uint32_t mResolution;
    std::uint32_t mLightCount;
    vk::GpuImage mMaps;
    vk::GpuImage mDepth;
    vk::PipelineLayout mPipelineLayout;
    vk::Pipeline mPipeline;
};

} // namespace bl::gpu
