// The classic alternative to a bundle: an orthographic depth map along omega (a directional
// shadow map), keeping only the surface nearest to a light at +infinity along omega. A point can
// use it for one direction only (omega), where a bundle answers omega and -omega for everyone:
// the comparison [TO12] makes. The map (r32f, linear depth in world units, -inf where empty) is in
// VK_IMAGE_LAYOUT_GENERAL after record().
#pragma once

#include "gpu/GpuScene.h"
#include "gpu/RecordedUniform.h"
#include "vk/Buffer.h"
#include "vk/BoundSet.h"
#include "vk/GpuTimer.h"
#include "vk/Pipeline.h"

#include <shared/BundleTypes.h>

namespace bl {

class DepthMapPass {
public:
    DepthMapPass(const vk::Context& ctx, const gpu::GpuScene& scene, std::uint32_t resolution);

    // Renders the map for `frame` (width and height at most the resolution). The frame is written
    // in the command stream: several records in one command buffer each use their own.
    void record(VkCommandBuffer cmd, const shader::BundleFrame& frame, double time, vk::GpuTimer* timer);

    const vk::GpuImage& map() const { return mMap; }
    VkBuffer frameBuffer() const { return mFrame.get(); }

private:
    const gpu::GpuScene* mScene;
    std::uint32_t mResolution;
    vk::GpuImage mMap;
    vk::GpuImage mDepth;
    gpu::RecordedUniform<shader::BundleFrame> mFrame;
    vk::BoundSet mBound;
    vk::PipelineLayout mPipelineLayout;
    vk::Pipeline mPipeline;
};

} // namespace bl
