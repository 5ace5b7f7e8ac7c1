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
    if (mLightCount == 0) {
        vk::ImageTransition placeholder = vk::toColorAttachment();
        placeholder.newLayout = VK_IMAGE_LAYOUT_GENERAL;
        vk::transitionImage(cmd, mMaps.get(), placeholder);
        return;
    }
    std::uint32_t scope = timer ? timer->start(cmd, "shadow maps") : 0;
    vk::transitionImage(cmd, mMaps.get(), vk::toColorAttachment());
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipeline.get());
    mScene->bindGeometry(cmd);
    for (std::uint32_t light = 0; light < mLightCount; ++light) {
        for (std::uint32_t face = 0; face < kFaces; ++face) {
            vk::transitionImage(cmd, mDepth.get(), vk::toDepthAttachment());
            vk::RenderTargets targets;
            targets.colors = {mMaps.layerView(kFaces * light + face)};
            targets.clearColor = {{std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 0.0f}};
            targets.depth = mDepth.view();
            targets.extent = {mResolution, mResolution};
            vk::beginRendering(cmd, targets);
            for (const GpuDraw& d : mScene->draws()) {
                shader::ShadowPush push{};
                push.model = mScene->modelMatrix(d.mesh, time);
                push.lightPosition = mScene->scene().lights[light].at(time).position;
                push.nearPlane = mScene->shadowNear();
                push.face = face;
                vkCmdPushConstants(cmd, mPipelineLayout.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                   0, sizeof(push), &push);
                vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
            }
            vkCmdEndRendering(cmd);
        }
    }
    vk::transitionImage(cmd, mMaps.get(), vk::colorAttachmentToGeneral());
    if (timer) {
        timer->stop(cmd, scope);
    }
}

} // namespace bl::gpu
