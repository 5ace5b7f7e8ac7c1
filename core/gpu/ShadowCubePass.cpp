#include "gpu/ShadowCubePass.h"

#include "vk/Commands.h"

#include <gpu/shadow_cube.frag.spv.h>
#include <gpu/shadow_cube.vert.spv.h>
#include <limits>

namespace bl::gpu {

namespace {
constexpr VkFormat kDistanceFormat = VK_FORMAT_R32_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr std::uint32_t kFaces = 6;
} // namespace

ShadowCubePass::ShadowCubePass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t resolution)
    : mScene(&scene), mResolution(resolution), mLightCount(static_cast<std::uint32_t>(scene.lights().size())) {
    VkDevice device = ctx.device();
    // Without lights a 1x1 placeholder keeps the shading pass's descriptors valid.
    const std::uint32_t side = mLightCount ? resolution : 1;
    mMaps = vk::GpuImage(ctx, {side, side, kFaces * std::max(mLightCount, 1u), kDistanceFormat,
                               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT, true});
    mDepth = vk::GpuImage(ctx, {side, side, 1, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT});
    mPipelineLayout = vk::makePipelineLayout(device, {}, sizeof(shader::ShadowPush),
                                             VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
    vk::GraphicsPipelineDesc desc;
    desc.vertexShader = kSpv_gpu_shadow_cube_vert;
    desc.fragmentShader = kSpv_gpu_shadow_cube_frag;
    desc.vertexBindings = GpuScene::vertexBindings();
    desc.vertexAttributes = {GpuScene::vertexAttributes()[0]}; // positions only
    desc.colorFormats = {kDistanceFormat};
    desc.depthFormat = kDepthFormat;
    desc.layout = mPipelineLayout.get();
    mPipeline = vk::makeGraphicsPipeline(device, desc);
}

void ShadowCubePass::record(VkCommandBuffer cmd, double time, vk::GpuTimer* timer) {
    vk::ImageTransition toAttachment;
    toAttachment.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    toAttachment.dstStage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    toAttachment.dstAccess = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
    vk::ImageTransition toGeneral;
    toGeneral.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    toGeneral.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    toGeneral.srcStage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    toGeneral.srcAccess = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
    toGeneral.dstStage = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    toGeneral.dstAccess = VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
    if (mLightCount == 0) {
        toAttachment.newLayout = VK_IMAGE_LAYOUT_GENERAL;
        vk::transitionImage(cmd, mMaps.get(), toAttachment);
        return;
    }
    std::uint32_t scope = timer ? timer->start(cmd, "shadow maps") : 0;
    vk::transitionImage(cmd, mMaps.get(), toAttachment);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipeline.get());
    mScene->bindGeometry(cmd);
    VkViewport viewport{0.0f, 0.0f, float(mResolution), float(mResolution), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {mResolution, mResolution}};
    for (std::uint32_t light = 0; light < mLightCount; ++light) {
        for (std::uint32_t face = 0; face < kFaces; ++face) {
            vk::ImageTransition dt;
            dt.newLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
            dt.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
            dt.srcStage = VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
            dt.srcAccess = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
            dt.dstStage = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
            dt.dstAccess = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
            vk::transitionImage(cmd, mDepth.get(), dt);

            VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            color.imageView = mMaps.layerView(kFaces * light + face);
            color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            color.clearValue.color = {{std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 0.0f}};
            VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            depth.imageView = mDepth.view();
            depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
            depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
            depth.clearValue.depthStencil = {0.0f, 0};
            VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
            info.renderArea = scissor;
            info.layerCount = 1;
            info.colorAttachmentCount = 1;
            info.pColorAttachments = &color;
            info.pDepthAttachment = &depth;
            vkCmdBeginRendering(cmd, &info);
            vkCmdSetViewport(cmd, 0, 1, &viewport);
            vkCmdSetScissor(cmd, 0, 1, &scissor);
            for (const GpuDraw& d : mScene->draws()) {
                shader::ShadowPush push{};
                push.model = mScene->modelMatrix(d.mesh, time);
                push.lightPosition = mScene->lights()[light].position;
                push.nearPlane = mScene->shadowNear();
                push.face = face;
                vkCmdPushConstants(cmd, mPipelineLayout.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                   0, sizeof(push), &push);
                vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
            }
            vkCmdEndRendering(cmd);
        }
    }
    vk::transitionImage(cmd, mMaps.get(), toGeneral);
    if (timer) {
        timer->stop(cmd, scope);
    }
}

} // namespace bl::gpu
