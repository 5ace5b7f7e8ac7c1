#include "modes/atlas/AtlasViewPass.h"

#include "base/Error.h"
#include "vk/Commands.h"

#include <modes/atlas/AtlasShared.h>
#include <modes/atlas/view.frag.spv.h>
#include <modes/atlas/view.vert.spv.h>

namespace bl::atlasmode {

namespace {
constexpr VkFormat kViewFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
} // namespace

AtlasViewPass::AtlasViewPass(const vk::Context& ctx, const gpu::GpuScene& scene, std::uint32_t width,
                             std::uint32_t height)
    : mScene(&scene), mWidth(width), mHeight(height) {
    if (!scene.hasAtlas()) {
        throw Error("atlas view pass: the GPU scene was built without an atlas link");
    }
    mImage = vk::GpuImage(ctx, {width, height, 1, kViewFormat,
                                VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT});
    mDepth = vk::GpuImage(ctx, {width, height, 1, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT});
    mLayout = vk::makePipelineLayout(ctx.device(), {}, sizeof(shader::AtlasViewPush), VK_SHADER_STAGE_VERTEX_BIT);
    vk::GraphicsPipelineDesc desc;
    desc.vertexShader = kSpv_modes_atlas_view_vert;
    desc.fragmentShader = kSpv_modes_atlas_view_frag;
    desc.vertexBindings = gpu::GpuScene::atlasVertexBindings();
    desc.vertexAttributes = gpu::GpuScene::atlasVertexAttributes();
    desc.colorFormats = {kViewFormat};
    desc.depthFormat = kDepthFormat;
    desc.layout = mLayout.get();
    mPipeline = vk::makeGraphicsPipeline(ctx.device(), desc);
}

void AtlasViewPass::record(VkCommandBuffer cmd, const gpu::CameraSample& s, vk::GpuTimer* timer) const {
    const std::uint32_t scope = timer ? timer->start(cmd, "atlas view") : 0;
    vk::transitionImage(cmd, mImage.get(), vk::toColorAttachment());
    vk::transitionImage(cmd, mDepth.get(), vk::toDepthAttachment());
    vk::RenderTargets targets;
    targets.colors = {mImage.view()};
    targets.depth = mDepth.view();
    targets.extent = {mWidth, mHeight};
    vk::beginRendering(cmd, targets);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipeline.get());
    mScene->bindGeometry(cmd);
    mScene->bindAtlasStream(cmd);
    // The G-buffer adds the jitter to clip x, y as jitter * w; the same as an NDC translation
    // applied after the projection.
    glm::mat4 jitter(1.0f);
    jitter[3][0] = s.jitterNdc.x;
    jitter[3][1] = s.jitterNdc.y;
    for (const gpu::GpuDraw& d : mScene->draws()) {
        shader::AtlasViewPush push{};
        push.viewProj = jitter * s.camera.viewProj;
        push.model = mScene->modelMatrix(d.mesh, s.time);
        vkCmdPushConstants(cmd, mLayout.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
        vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
    }
    vkCmdEndRendering(cmd);
    vk::transitionImage(cmd, mImage.get(), vk::colorAttachmentToGeneral());
    if (timer) {
        timer->stop(cmd, scope);
    }
}

} // namespace bl::atlasmode
