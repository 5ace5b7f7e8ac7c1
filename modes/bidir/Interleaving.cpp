#include "modes/bidir/Interleaving.h"

#include "vk/Commands.h"

#include <cstring>
#include <modes/bidir/BidirShared.h>
#include <modes/bidir/Interleave.h>
#include <modes/bidir/interleave.comp.spv.h>

namespace bl {

Interleaving::Interleaving(const vk::Context& ctx, std::uint32_t width, std::uint32_t height,
                           const InterleaveOptions& options)
    : mContext(&ctx), mWidth(width), mHeight(height), mOptions(options) {
    const bool on = active();
    mFrame = vk::GpuImage(ctx, {on ? width : 1u, on ? height : 1u, shader::kPathLayerCount,
                                VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                true});
    const bool temporal = on && options.temporal;
    mCaches = vk::GpuImage(ctx, {temporal ? width : 1u, temporal ? height : 1u, shader::kTemporalCacheLayers,
                                 VK_FORMAT_R32G32B32A32_SFLOAT,
                                 VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                     VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                 true});
    mCacheInfo = vk::Buffer(ctx, sizeof(shader::InterleaveCache) * shader::kTemporalCaches,
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload);
    std::memset(mCacheInfo.data(), 0, sizeof(shader::InterleaveCache) * shader::kTemporalCaches);
    mEvaluate = vk::Buffer(ctx, sizeof(shader::InterleaveEvaluate), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           vk::MemoryUse::Upload);
    const shader::InterleaveEvaluate evaluate{options.n, on ? 1u : 0u, options.n > 1 && options.filter ? 1u : 0u, 0u};
    std::memcpy(mEvaluate.data(), &evaluate, sizeof(evaluate));
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        VkClearColorValue zero{};
        VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
        for (VkImage image : {mFrame.get(), mCaches.get()}) {
            vk::transitionImage(cmd, image, vk::ImageTransition{});
            vkCmdClearColorImage(cmd, image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
        }
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    });

    VkDevice device = ctx.device();
    mBound = vk::BoundSet(device, {vk::Bound::storageImage(shader::kInterleaveBindingFrame, mFrame.view()),
                                   vk::Bound::storageImage(shader::kInterleaveBindingCaches, mCaches.view()),
                                   vk::Bound::storageBuffer(shader::kInterleaveBindingCameras, mCacheInfo.get())});
}

bool Interleaving::matches(std::uint32_t width, std::uint32_t height, const InterleaveOptions& o) const {
    return width == mWidth && height == mHeight && o.n == mOptions.n && o.filter == mOptions.filter &&
           o.temporal == mOptions.temporal && o.twoSigma2 == mOptions.twoSigma2;
}

void Interleaving::preparePipeline(VkDescriptorSetLayout cameraSetLayout) {
    VkDevice device = mContext->device();
    mFilter = vk::ComputePass<shader::InterleavePush>(device, kSpv_modes_bidir_interleave_comp,
                                                      {cameraSetLayout, mBound.layout()});
}

std::uint32_t Interleaving::dispatchWidth() const {
    return mOptions.n * static_cast<std::uint32_t>(shader::blInterleaveBlock(mWidth, mHeight, mOptions.n).x);
}

std::uint32_t Interleaving::dispatchHeight() const {
    return mOptions.n * static_cast<std::uint32_t>(shader::blInterleaveBlock(mWidth, mHeight, mOptions.n).y);
}

std::uint64_t Interleaving::sequenceBase(std::uint32_t iteration, std::uint32_t pairs) const {
    const std::uint64_t set = mOptions.temporal ? mUpdates % shader::kTemporalCaches : iteration;
    return set * pairs;
}

gpu::CameraSample Interleaving::cameraSample(const gpu::CameraSample& jittered, std::uint32_t width,
                                             std::uint32_t height) const {
    if (!mOptions.temporal) {
        return jittered;
    }
    gpu::CameraSample s = jittered;
    s.samplePosition = shader::blTemporalSubPixel(static_cast<std::uint32_t>(mUpdates % shader::kTemporalCaches));
    s.jitterNdc = (s.samplePosition - 0.5f) * glm::vec2(2.0f / float(width), 2.0f / float(height));
    return s;
}

Image Interleaving::cacheHits() const {
    Image out(static_cast<int>(mWidth), static_cast<int>(mHeight));
    if (!mOptions.temporal) {
        return out;
    }
    const std::vector<std::byte> raw = mCaches.download(*mContext, VK_IMAGE_LAYOUT_GENERAL, shader::kTemporalHitsLayer);
    const auto* texels = reinterpret_cast<const glm::vec4*>(raw.data());
    for (std::size_t i = 0; i < out.pixelCount(); ++i) out.pixels()[i] = glm::vec3(texels[i].x);
    return out;
}

void Interleaving::recordClear(VkCommandBuffer cmd) const {
    VkClearColorValue dropped{};
    dropped.float32[3] = shader::kFrameDropped;
    VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
    vkCmdClearColorImage(cmd, mFrame.get(), VK_IMAGE_LAYOUT_GENERAL, &dropped, 1, &all);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
}

void Interleaving::recordResolve(VkCommandBuffer cmd, VkDescriptorSet cameraSet, const shader::GpuCamera& camera,
                                 vk::GpuTimer* timer) {
    const auto cache = static_cast<std::uint32_t>(mUpdates % shader::kTemporalCaches);
    if (mOptions.temporal) {
        // The shader reads only the other caches' records: this one's may change before it runs.
        auto* info = static_cast<shader::InterleaveCache*>(mCacheInfo.data());
        info[cache].camera = camera;
        info[cache].valid = 1u;
    }
    shader::InterleavePush push{};
    push.width = mWidth;
    push.height = mHeight;
    push.interleave = mOptions.n;
    push.blur = mOptions.filter ? 1u : 0u;
    push.temporal = mOptions.temporal ? 1u : 0u;
    push.cache = cache;
    push.reproject = mOptions.reproject ? 1u : 0u;
    push.twoSigma2 = mOptions.twoSigma2;
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    const std::uint32_t scope = timer ? timer->start(cmd, "interleave filter/reconstruct") : 0;
    const VkDescriptorSet sets[] = {cameraSet, mBound.set()};
    mFilter.dispatch(cmd, push,
                     {vk::groupCount(mWidth, shader::kInterleaveGroupSize), vk::groupCount(mHeight, shader::kInterleaveGroupSize), 1},
                     sets);
    if (timer) timer->stop(cmd, scope);
}

} // namespace bl
