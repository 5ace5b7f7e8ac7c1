#include "bundle/DepthMapPass.h"

#include "bundle/BundleFrame.h"
#include "vk/Commands.h"

#include <bundle/depth_map.frag.spv.h>
#include <bundle/depth_map.vert.spv.h>
#include <algorithm>
#include <limits>

namespace bl {

namespace {
// Depth (r) and the normal of the surface's facet (gba): bundle/DepthMapVisibility.glsl.
constexpr VkFormat kMapFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
} // namespace

VkDeviceSize DepthMapPass::bytesFor(std::uint32_t resolution, std::uint32_t layers) {
    const VkDeviceSize texels = VkDeviceSize(resolution) * resolution;
    return texels * (vk::bytesPerTexel(kMapFormat) * std::max(layers, 1u) + vk::bytesPerTexel(kDepthFormat));
}

DepthMapPass::DepthMapPass(const vk::Context& ctx, const gpu::GpuScene& scene, std::uint32_t resolution,
                           std::uint32_t layers)
    : mScene(&scene), mResolution(resolution), mArray(layers > 0) {
    VkDevice device = ctx.device();
    mMap = vk::GpuImage(ctx, {resolution, resolution, std::max(layers, 1u), kMapFormat,
                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                                  VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                              mArray});
    mDepth = vk::GpuImage(ctx, {resolution, resolution, 1, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT});
    mFrame = gpu::RecordedUniform<shader::BundleFrame>(ctx);
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    mBound = vk::BoundSet(device, {vk::Bound::uniformBuffer(0, mFrame.get())}, stages);
    VkDescriptorSetLayout layouts[] = {mBound.layout()};
    mPipelineLayout = vk::makePipelineLayout(device, layouts, sizeof(shader::BundleDepthMapPush), VK_SHADER_STAGE_VERTEX_BIT);
    vk::GraphicsPipelineDesc desc;
    desc.vertexShader = kSpv_bundle_depth_map_vert;
    desc.fragmentShader = kSpv_bundle_depth_map_frag;
    desc.vertexBindings = gpu::GpuScene::vertexBindings();
    desc.vertexAttributes = gpu::GpuScene::vertexAttributes();
    desc.colorFormats = {kMapFormat};
    desc.depthFormat = kDepthFormat;
    desc.depthCompare = VK_COMPARE_OP_GREATER; // largest depth along omega: nearest to the light
    desc.layout = mPipelineLayout.get();
    mPipeline = vk::makeGraphicsPipeline(device, desc);

    // Every layer starts as "nothing in the way" (-inf) in GENERAL, so a layer not rendered in an
    // iteration (a direction without light) is still valid to bind, and each record changes the
    // layout of its own layer only.
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        vk::transitionImage(cmd, mMap.get(), vk::ImageTransition{});
        const VkClearColorValue nothing{{-std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 0.0f}};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
        vkCmdClearColorImage(cmd, mMap.get(), VK_IMAGE_LAYOUT_GENERAL, &nothing, 1, &all);
    });
}

void DepthMapPass::record(VkCommandBuffer cmd, const shader::BundleFrame& frame, double time, vk::GpuTimer* timer,
                          std::uint32_t layer) {
    std::uint32_t scope = timer ? timer->start(cmd, "depth map") : 0;
    mFrame.record(cmd, frame);
    // Only this layer changes layout (its old map is discarded); the others keep theirs.
    vk::ImageTransition toAttachment = vk::toColorAttachment();
    toAttachment.baseLayer = layer;
    toAttachment.layerCount = 1;
    vk::transitionImage(cmd, mMap.get(), toAttachment);
    vk::transitionImage(cmd, mDepth.get(), vk::toDepthAttachment());
    vk::RenderTargets targets;
    targets.colors = {mArray ? mMap.layerView(layer) : mMap.view()};
    targets.clearColor = {{-std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 0.0f}};
    targets.depth = mDepth.view();
    targets.clearDepth = 0.0f;
    targets.extent = {frame.width, frame.height};
    targets.viewport = bundleViewport(frame);
    vk::beginRendering(cmd, targets);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipelineLayout.get(), 0, 1, mBound.sets().data(), 0, nullptr);
    mScene->bindGeometry(cmd);
    shader::BundleDepthMapPush push{};
    for (const gpu::GpuDraw& d : mScene->draws()) {
        push.model = mScene->modelMatrix(d.mesh, time);
        vkCmdPushConstants(cmd, mPipelineLayout.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
        vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
    }
    vkCmdEndRendering(cmd);
    vk::ImageTransition toGeneral = vk::colorAttachmentToGeneral();
    toGeneral.baseLayer = layer;
    toGeneral.layerCount = 1;
    vk::transitionImage(cmd, mMap.get(), toGeneral);
    if (timer) {
        timer->stop(cmd, scope);
    }
}

} // namespace bl
