#include "gpu/GBufferPass.h"

#include "vk/Commands.h"

#include <algorithm>

#include <gpu/gbuffer.frag.spv.h>
#include <gpu/gbuffer.vert.spv.h>

namespace bl::gpu {

namespace {
constexpr VkFormat kAttachmentFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
} // namespace

GBufferPass::GBufferPass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t width, std::uint32_t height,
                         GBufferSurface surface)
    : mScene(&scene), mWidth(width), mHeight(height) {
    VkDevice device = ctx.device();
    for (vk::GpuImage& a : mAttachments) {
        a = vk::GpuImage(ctx, {width, height, 1, kAttachmentFormat,
                               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT});
    }
    mDepth = vk::GpuImage(ctx, {width, height, 1, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT});
    mCamera = RecordedUniform<shader::GpuCamera>(ctx);

    const VkShaderStageFlags both = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    mFrame = vk::BoundSet(device,
                          {vk::Bound::uniformBuffer(shader::kGBufferBindingCamera, mCamera.get()).visibleTo(both),
                           vk::Bound::storageBuffer(shader::kGBufferBindingMaterials, scene.materialBuffer()),
                           vk::Bound::storageBuffer(shader::kGBufferBindingVertices, scene.vertexBuffer()),
                           vk::Bound::storageBuffer(shader::kGBufferBindingIndices, scene.indexBuffer())},
                          VK_SHADER_STAGE_FRAGMENT_BIT);
    // One set per material, all of one layout: a pool of those, written apart.
    mMaterialLayout = vk::makeDescriptorSetLayout(
        device, {{shader::kGBufferBindingAlbedoTexture, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                  VK_SHADER_STAGE_FRAGMENT_BIT}});
    const auto materialCount = static_cast<std::uint32_t>(scene.scene().materials.size());
    mPool = vk::DescriptorPool(device, std::max(materialCount, 1u), std::max(materialCount, 1u));
    for (std::uint32_t m = 0; m < materialCount; ++m) {
        VkDescriptorSet set = mPool.allocate(mMaterialLayout.get());
        vk::DescriptorWriter()
            .image(shader::kGBufferBindingAlbedoTexture, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                   scene.materialTexture(m), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, scene.textureSampler())
            .update(device, set);
        mMaterialSets.push_back(set);
    }

    VkDescriptorSetLayout sets[] = {mFrame.layout(), mMaterialLayout.get()};
    mPipelineLayout = vk::makePipelineLayout(device, sets, sizeof(shader::GBufferPush), both);
    vk::GraphicsPipelineDesc desc;
    desc.vertexShader = kSpv_gpu_gbuffer_vert;
    desc.fragmentShader = kSpv_gpu_gbuffer_frag;
    desc.vertexBindings = GpuScene::vertexBindings();
    desc.vertexAttributes = GpuScene::vertexAttributes();
    desc.colorFormats.assign(shader::kGBufferAttachmentCount, kAttachmentFormat);
    desc.depthFormat = kDepthFormat;
    desc.layout = mPipelineLayout.get();
    desc.specialization.assign(shader::kGBufferSpecCount, 0u);
    desc.specialization[shader::kGBufferSpecTextured] = scene.scene().features().textured ? 1u : 0u;
    desc.specialization[shader::kGBufferSpecSurface] = surface == GBufferSurface::Written ? 1u : 0u;
    mPipeline = vk::makeGraphicsPipeline(device, desc);
}

void GBufferPass::record(VkCommandBuffer cmd, const shader::GpuCamera& camera, glm::vec2 jitterNdc, double time,
                         vk::GpuTimer* timer) {
    std::uint32_t scope = timer ? timer->start(cmd, "gbuffer") : 0;
    mCamera.record(cmd, camera);

    vk::RenderTargets targets;
    for (vk::GpuImage& a : mAttachments) {
        vk::transitionImage(cmd, a.get(), vk::toColorAttachment());
        targets.colors.push_back(a.view());
    }
    vk::transitionImage(cmd, mDepth.get(), vk::toDepthAttachment());
    targets.depth = mDepth.view();
    targets.extent = {mWidth, mHeight};
    vk::beginRendering(cmd, targets);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipelineLayout.get(), 0, 1, mFrame.sets().data(), 0,
                            nullptr);
    mScene->bindGeometry(cmd);
    for (const GpuDraw& d : mScene->draws()) {
        const Mesh& mesh = mScene->scene().meshes[d.mesh];
        shader::GBufferPush push{};
        push.model = mScene->modelMatrix(d.mesh, time);
        push.emission = mesh.emission;
        push.material = mesh.material;
        push.jitter = jitterNdc;
        push.firstTriangle = d.firstIndex / 3;
        push.vertexOffset = static_cast<std::uint32_t>(d.vertexOffset);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipelineLayout.get(), 1, 1,
                                &mMaterialSets[mesh.material], 0, nullptr);
        vkCmdPushConstants(cmd, mPipelineLayout.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(push), &push);
        vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
    }
    vkCmdEndRendering(cmd);

    for (vk::GpuImage& a : mAttachments) {
        vk::transitionImage(cmd, a.get(), vk::colorAttachmentToGeneral());
    }
    if (timer) {
        timer->stop(cmd, scope);
    }
}

std::vector<glm::vec3> GBufferPass::visiblePoints(const vk::Context& ctx) const {
    const std::size_t pixels = std::size_t(mWidth) * mHeight;
    if (!mPositionReadback) {
        mPositionReadback = std::make_unique<vk::Buffer>(ctx, VkDeviceSize(pixels * sizeof(glm::vec4)),
                                                         VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);
    }
    mAttachments[shader::kGBufferPosition].downloadInto(ctx, VK_IMAGE_LAYOUT_GENERAL, *mPositionReadback);
    const auto* p = static_cast<const glm::vec4*>(mPositionReadback->data());
    std::vector<glm::vec3> points;
    points.reserve(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
        if (p[i].w > 0.0f) points.emplace_back(p[i]);
    }
    return points;
}

} // namespace bl::gpu
