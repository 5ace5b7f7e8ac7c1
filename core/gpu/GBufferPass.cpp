#include "gpu/GBufferPass.h"

#include "vk/Commands.h"

#include <gpu/gbuffer.frag.spv.h>
#include <gpu/gbuffer.vert.spv.h>

namespace bl::gpu {

namespace {
constexpr VkFormat kAttachmentFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
} // namespace

GBufferPass::GBufferPass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t width, std::uint32_t height)
    : mScene(&scene), mWidth(width), mHeight(height) {
    VkDevice device = ctx.device();
    for (vk::GpuImage& a : mAttachments) {
        a = vk::GpuImage(ctx, {width, height, 1, kAttachmentFormat,
                               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT});
    }
    mDepth = vk::GpuImage(ctx, {width, height, 1, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT});
    mCamera = vk::Buffer(ctx, sizeof(shader::GpuCamera), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUse::Upload);

    const VkShaderStageFlags both = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    mFrameLayout = vk::makeDescriptorSetLayout(
        device, {{shader::kGBufferBindingCamera, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, both},
                 {shader::kGBufferBindingMaterials, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT}});
    mMaterialLayout = vk::makeDescriptorSetLayout(
        device, {{shader::kGBufferBindingAlbedoTexture, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                  VK_SHADER_STAGE_FRAGMENT_BIT}});
    const auto materialCount = static_cast<std::uint32_t>(scene.scene().materials.size());
    mPool = vk::DescriptorPool(device, materialCount + 1, materialCount + 2);
    mFrameSet = mPool.allocate(mFrameLayout.get());
    vk::DescriptorWriter()
        .buffer(shader::kGBufferBindingCamera, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, mCamera.get())
        .buffer(shader::kGBufferBindingMaterials, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, scene.materialBuffer())
        .update(device, mFrameSet);
    for (std::uint32_t m = 0; m < materialCount; ++m) {
        VkDescriptorSet set = mPool.allocate(mMaterialLayout.get());
        vk::DescriptorWriter()
            .image(shader::kGBufferBindingAlbedoTexture, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                   scene.materialTexture(m), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, scene.textureSampler())
            .update(device, set);
        mMaterialSets.push_back(set);
    }

    VkDescriptorSetLayout sets[] = {mFrameLayout.get(), mMaterialLayout.get()};
    mPipelineLayout = vk::makePipelineLayout(device, sets, sizeof(shader::GBufferPush), both);
    vk::GraphicsPipelineDesc desc;
    desc.vertexShader = kSpv_gpu_gbuffer_vert;
    desc.fragmentShader = kSpv_gpu_gbuffer_frag;
    desc.vertexBindings = GpuScene::vertexBindings();
    desc.vertexAttributes = GpuScene::vertexAttributes();
    desc.colorFormats.assign(shader::kGBufferAttachmentCount, kAttachmentFormat);
    desc.depthFormat = kDepthFormat;
    desc.layout = mPipelineLayout.get();
    mPipeline = vk::makeGraphicsPipeline(device, desc);
}

void GBufferPass::record(VkCommandBuffer cmd, const shader::GpuCamera& camera, glm::vec2 jitterNdc, double time,
                         vk::GpuTimer* timer) {
    std::memcpy(mCamera.data(), &camera, sizeof(camera));
    std::uint32_t scope = timer ? timer->start(cmd, "gbuffer") : 0;

    std::array<VkRenderingAttachmentInfo, shader::kGBufferAttachmentCount> colors{};
    for (std::uint32_t i = 0; i < colors.size(); ++i) {
        vk::ImageTransition t;
        t.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        t.dstStage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
        t.dstAccess = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
        vk::transitionImage(cmd, mAttachments[i].get(), t);
        colors[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        colors[i].imageView = mAttachments[i].view();
        colors[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        colors[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        colors[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        colors[i].clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
    }
    vk::ImageTransition dt;
    dt.newLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    dt.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    dt.dstStage = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
    dt.dstAccess = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    vk::transitionImage(cmd, mDepth.get(), dt);
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = mDepth.view();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.clearValue.depthStencil = {0.0f, 0}; // reversed depth: 0 is infinitely far

    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {mWidth, mHeight}};
    info.layerCount = 1;
    info.colorAttachmentCount = static_cast<std::uint32_t>(colors.size());
    info.pColorAttachments = colors.data();
    info.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &info);
    VkViewport viewport{0.0f, 0.0f, float(mWidth), float(mHeight), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {mWidth, mHeight}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipelineLayout.get(), 0, 1, &mFrameSet, 0,
                            nullptr);
    mScene->bindGeometry(cmd);
    for (const GpuDraw& d : mScene->draws()) {
        const Mesh& mesh = mScene->scene().meshes[d.mesh];
        shader::GBufferPush push{};
        push.model = mScene->modelMatrix(d.mesh, time);
        push.emission = mesh.emission;
        push.material = mesh.material;
        push.jitter = jitterNdc;
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipelineLayout.get(), 1, 1,
                                &mMaterialSets[mesh.material], 0, nullptr);
        vkCmdPushConstants(cmd, mPipelineLayout.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(push), &push);
        vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
    }
    vkCmdEndRendering(cmd);

    for (vk::GpuImage& a : mAttachments) {
        vk::ImageTransition t;
        t.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        t.newLayout = VK_IMAGE_LAYOUT_GENERAL;
        t.srcStage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
        t.srcAccess = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
        t.dstStage = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT;
        t.dstAccess = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT;
        vk::transitionImage(cmd, a.get(), t);
    }
    if (timer) {
        timer->stop(cmd, scope);
    }
}

} // namespace bl::gpu
