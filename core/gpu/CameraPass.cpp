#include "gpu/CameraPass.h"

#include "sampling/PixelSamples.h"

#include <shared/Bindings.h>

namespace bl::gpu {

CameraPass::CameraPass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t width, std::uint32_t height,
                       std::uint32_t layers)
    : mScene(&scene), mGBuffer(std::make_unique<GBufferPass>(ctx, scene, width, height)),
      mAccumulator(ctx, width, height, layers) {
    VkDevice device = ctx.device();
    std::vector<VkImageView> gbuffer;
    for (std::uint32_t i = 0; i < shader::kGBufferAttachmentCount; ++i) gbuffer.push_back(mGBuffer->attachment(i).view());
    mBound = vk::BoundSet(
        device, {vk::Bound::storageImages(shader::kCameraBindingGBuffer, gbuffer),
                 vk::Bound::uniformBuffer(shader::kCameraBindingCamera, mGBuffer->cameraBuffer()),
                 vk::Bound::storageBuffer(shader::kCameraBindingMaterials, scene.materialBuffer()),
                 vk::Bound::sampledImage(shader::kCameraBindingEnvironment, scene.environmentView(),
                                         scene.environmentSampler()),
                 vk::Bound::storageImage(shader::kCameraBindingAccum, mAccumulator.view())});
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
