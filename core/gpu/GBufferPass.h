// Rasterizes the scene from the camera into the G-buffer of Bindings.h (rgba32f attachments +
// reversed depth). After record() the attachments are in VK_IMAGE_LAYOUT_GENERAL, ready to be read
// as storage images by a shading pass.
#pragma once

#include "gpu/GpuScene.h"
#include "gpu/RecordedUniform.h"
#include "vk/Buffer.h"
#include "vk/BoundSet.h"
#include "vk/GpuTimer.h"
#include "vk/Pipeline.h"

#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <vector>
#include <shared/Bindings.h>

namespace bl::gpu {

// Whether a G-buffer's reader decodes the surface attachment (kGBufferSurface): without it that
// attachment holds zeros and the pass skips the barycentrics (Bindings.h).
enum class GBufferSurface { Written, Unused };

class GBufferPass {
public:
    // Device memory per pixel: the rgba32f attachments and a 32-bit depth.
    static constexpr VkDeviceSize kBytesPerPixel = shader::kGBufferAttachmentCount * 16 + 4;

    GBufferPass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t width, std::uint32_t height,
                GBufferSurface surface = GBufferSurface::Written);

    // Records the camera's upload and the pass: several records in one command buffer each see
    // their own camera, and cameraBuffer() holds the last recorded one for later passes.
    // `jitterNdc` shifts the sample position inside each pixel, in NDC units.
    void record(VkCommandBuffer cmd, const shader::GpuCamera& camera, glm::vec2 jitterNdc, double time,
                vk::GpuTimer* timer);

    const vk::GpuImage& attachment(std::uint32_t i) const { return mAttachments[i]; }
    // The positions of the pixels that see a surface (the position attachment's w > 0), downloaded
    // after the last record() completed: the points a bundle frame fitted to the camera-visible
    // points must cover ([TO12s] B.1, bundleFrameForPoints).
    std::vector<glm::vec3> visiblePoints(const vk::Context& ctx) const;
    VkBuffer cameraBuffer() const { return mCamera.get(); }
    std::uint32_t width() const { return mWidth; }
    std::uint32_t height() const { return mHeight; }

private:
    const GpuScene* mScene;
    std::uint32_t mWidth, mHeight;
    std::array<vk::GpuImage, shader::kGBufferAttachmentCount> mAttachments;
    vk::GpuImage mDepth;
    RecordedUniform<shader::GpuCamera> mCamera;
    vk::BoundSet mFrame;
    vk::DescriptorSetLayout mMaterialLayout;
    vk::DescriptorPool mPool;
    std::vector<VkDescriptorSet> mMaterialSets;
    vk::PipelineLayout mPipelineLayout;
    vk::Pipeline mPipeline;
    // visiblePoints' readback of the position attachment, made on first use and kept: modes that
    // fit bundles to the visible points read it back every frame.
    mutable std::unique_ptr<vk::Buffer> mPositionReadback;
};

} // namespace bl::gpu
