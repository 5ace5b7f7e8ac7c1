#include "gpu/CameraPass.h"

#include "sampling/PixelSamples.h"

#include <shared/Bindings.h>

namespace bl::gpu {

namespace {
// Bindings of the camera set, counted for the pool: G-buffer array, camera, materials,
// environment, accumulator.
constexpr std::uint32_t kCameraSetDescriptors = shader::kGBufferAttachmentCount + 4;
} // namespace

CameraPass::CameraPass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t width, std::uint32_t height,
                       std::uint32_t layers)
    : mScene(&scene), mGBuffer(std::make_unique<GBufferPass>(ctx, scene, width, height)),
      mAccumulator(ctx, width, height, layers) {
    VkDevice device = ctx.device();
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    mSetLayout = vk::makeDescriptorSetLayout(
        device,
        {{shader::kCameraBindingGBuffer, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs, shader::kGBufferAttachmentCount},
         {shader::kCameraBindingCamera, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs},
         {shader::kCameraBindingMaterials, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
         {shader::kCameraBindingEnvironment, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs},
         {shader::kCameraBindingAccum, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs}});
    mPool = vk::DescriptorPool(device, 1, kCameraSetDescriptors);
    mSet = mPool.allocate(mSetLayout.get());
    vk::DescriptorWriter writer;
    for (std::uint32_t i = 0; i < shader::kGBufferAttachmentCount; ++i) {
        writer.image(shader::kCameraBindingGBuffer, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, mGBuffer->attachment(i).view(),
                     VK_IMAGE_LAYOUT_GENERAL, VK_NULL_HANDLE, i);
    }
    writer.buffer(shader::kCameraBindingCamera, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, mGBuffer->cameraBuffer())
        .buffer(shader::kCameraBindingMaterials, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, scene.materialBuffer())
        .image(shader::kCameraBindingEnvironment, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, scene.environmentView(),
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, scene.environmentSampler())
        .image(shader::kCameraBindingAccum, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, mAccumulator.view(),
               VK_IMAGE_LAYOUT_GENERAL)
        .update(device, mSet);
}

VkDeviceSize CameraPass::bytesPerPixel(std::uint32_t layers) {
    return GBufferPass::kBytesPerPixel + Accumulator::bytesPerPixel(layers);
}

CameraSample CameraPass::sample(std::uint32_t k, bool jitter, double time, std::uint64_t seed) const {
    CameraSample s;
    s.samplePosition = pixelSamplePosition(k, jitter, seed);
    s.jitterNdc = (s.samplePosition - 0.5f) * glm::vec2(2.0f / float(width()), 2.0f / float(height()));
    s.camera = makeGpuCamera(mScene->scene().camera, time, mScene->cameraNear());
    s.time = time;
    return s;
}

void CameraPass::record(VkCommandBuffer cmd, const CameraSample& s, vk::GpuTimer* timer) {
    mGBuffer->record(cmd, s.camera, s.jitterNdc, s.time, timer);
}

} // namespace bl::gpu
