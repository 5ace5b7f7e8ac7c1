// Mode atlas's camera lookup raster: the scene drawn from the camera on the atlas's vertices
// (GpuScene built with an atlas link), writing each pixel's atlas uv, page and the side of the
// surface the camera sees into one rgba32f image (shaders/modes/atlas/AtlasShared.h). The shared
// G-buffer (core/gpu/GBufferPass.h) carries no atlas uv, so the mode draws its own; it uses the
// same camera, jitter and rasterization rules, so both see the same surface in every pixel.
#pragma once

#include "gpu/CameraPass.h"
#include "gpu/GpuScene.h"
#include "vk/GpuImage.h"
#include "vk/GpuTimer.h"
#include "vk/Pipeline.h"

namespace bl::atlasmode {

class AtlasViewPass {
public:
    AtlasViewPass(const vk::Context& ctx, const gpu::GpuScene& scene, std::uint32_t width, std::uint32_t height);

    // Records the raster of sample `s`; the image is left in VK_IMAGE_LAYOUT_GENERAL for compute reads.
    void record(VkCommandBuffer cmd, const gpu::CameraSample& s, vk::GpuTimer* timer) const;

    const vk::GpuImage& image() const { return mImage; }

private:
    const gpu::GpuScene* mScene;
    std::uint32_t mWidth, mHeight;
    vk::GpuImage mImage;
    vk::GpuImage mDepth;
    vk::PipelineLayout mLayout;
    vk::Pipeline mPipeline;
};

} // namespace bl::atlasmode
