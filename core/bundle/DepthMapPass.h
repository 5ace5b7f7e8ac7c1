// The classic alternative to a bundle: an orthographic depth map along omega (a directional
// shadow map), keeping only the surface nearest to a light at +infinity along omega. A point can
// use it for one direction only (omega), where a bundle answers omega and -omega for everyone:
// the comparison [TO12] makes. The map (rgba32f: linear depth in world units, -inf where empty, and
// the geometric normal of the surface's facet, whose plane the visibility test judges x's ray
// against and finds creases with: bundle/DepthMapVisibility.glsl) is in
// VK_IMAGE_LAYOUT_GENERAL after record(). With `layers` > 0 the image is a 2D array of that many
// maps (one per direction: EnvironmentShadowPass), each record rendering one layer.
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
    // `layers` = 0: one map, viewed as a 2D image; else a 2D array of `layers` maps.
    DepthMapPass(const vk::Context& ctx, const gpu::GpuScene& scene, std::uint32_t resolution, std::uint32_t layers = 0);

    // Device memory of the maps and their depth buffer (for a check before allocating).
    static VkDeviceSize bytesFor(std::uint32_t resolution, std::uint32_t layers);

    // Renders the map for `frame` (width and height at most the resolution) into `layer` (the
    // other layers keep theirs). The frame is written in the command stream: several records in one
    // command buffer each use their own.
    void record(VkCommandBuffer cmd, const shader::BundleFrame& frame, double time, vk::GpuTimer* timer,
                std::uint32_t layer = 0);

    const vk::GpuImage& map() const { return mMap; }
    VkBuffer frameBuffer() const { return mFrame.get(); }

private:
    const gpu::GpuScene* mScene;
    std::uint32_t mResolution;
    bool mArray = false;
    vk::GpuImage mMap;
    vk::GpuImage mDepth;
    gpu::RecordedUniform<shader::BundleFrame> mFrame;
    vk::BoundSet mBound;
    vk::PipelineLayout mPipelineLayout;
    vk::Pipeline mPipeline;
};

} // namespace bl
