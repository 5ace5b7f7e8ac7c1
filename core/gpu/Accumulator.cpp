#include "gpu/Accumulator.h"

#include "base/Error.h"
#include "vk/Commands.h"

#include <algorithm>

namespace bl::gpu {

namespace {
constexpr VkFormat kSlotFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkDeviceSize kBytesPerSlot = 16; // rgba32f

// One slot's texels, read back.
std::vector<glm::vec4> downloadSlot(const vk::Context& ctx, const vk::GpuImage& image, std::uint32_t slot) {
    std::vector<std::byte> raw = image.download(ctx, VK_IMAGE_LAYOUT_GENERAL, slot);
    const auto* texels = reinterpret_cast<const glm::vec4*>(raw.data());
    return {texels, texels + raw.size() / sizeof(glm::vec4)};
}

// The compensated sums of a slot pair, in double.
std::vector<glm::dvec3> downloadSums(const vk::Context& ctx, const vk::GpuImage& image, std::uint32_t sumSlot) {
    std::vector<glm::vec4> sums = downloadSlot(ctx, image, sumSlot);
    std::vector<glm::vec4> errors = downloadSlot(ctx, image, sumSlot + 1);
    std::vector<glm::dvec3> out(sums.size());
    for (std::size_t i = 0; i < sums.size(); ++i) {
        out[i] = glm::dvec3(glm::vec3(sums[i])) + glm::dvec3(glm::vec3(errors[i]));
    }
    return out;
}
} // namespace

Accumulator::Accumulator(const vk::Context& ctx, std::uint32_t width, std::uint32_t height, std::uint32_t layers)
    : mLayers(layers) {
    if (layers == 0 || (layers & ~shader::kAllPathLayers) != 0) {
        throw Error("accumulator: layer mask " + std::to_string(layers) + " is empty or names a layer beyond " +
                    std::to_string(shader::kPathLayerCount));
    }
    mImage = vk::GpuImage(ctx, {width, height, shader::blAccumSlotCount(layers), kSlotFormat,
                                VK_IMAGE_USAGE_STORAGE_BIT, true});
    clear(ctx);
}

VkDeviceSize Accumulator::bytesPerPixel(std::uint32_t layers) {
    return kBytesPerSlot * shader::blAccumSlotCount(layers);
}

void Accumulator::clear(const vk::Context& ctx) {
    ctx.submitAndWait([&](VkCommandBuffer cmd) { recordClear(cmd); });
}

void Accumulator::recordClear(VkCommandBuffer cmd) const {
    vk::transitionImage(cmd, mImage.get(), vk::ImageTransition{});
    VkClearColorValue zero{};
    VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
    vkCmdClearColorImage(cmd, mImage.get(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
}

AccumulatedImages Accumulator::resolve(const vk::Context& ctx, std::uint32_t expected) const {
    const int width = static_cast<int>(mImage.desc().width);
    const int height = static_cast<int>(mImage.desc().height);
    const std::vector<glm::vec4> totals = downloadSlot(ctx, mImage, shader::kAccumTotalSum);
    const std::vector<glm::vec4> totalErrors = downloadSlot(ctx, mImage, shader::kAccumTotalError);
    const std::vector<glm::dvec3> sums = downloadSums(ctx, mImage, shader::kAccumTotalSum);
    const std::vector<glm::dvec3> squares = downloadSums(ctx, mImage, shader::kAccumSquareSum);

    AccumulatedImages out;
    out.expectedSamples = std::uint64_t(expected) * std::uint64_t(width) * std::uint64_t(height);
    Image mean(width, height), variance(width, height);
    for (std::size_t i = 0; i < mean.pixelCount(); ++i) {
        const auto added = static_cast<std::uint32_t>(totals[i].w);
        const auto refused = static_cast<std::uint32_t>(totalErrors[i].w);
        out.nonFiniteSamples += refused;
        out.droppedSamples += expected - std::min(added + refused, expected);
        if (added == 0) continue;
        const double n = added;
        const glm::dvec3 m = sums[i] / n;
        mean.pixels()[i] = glm::vec3(m);
        if (added > 1) {
            // Unbiased sample variance from the two moments, over n for the variance of the mean.
            const glm::dvec3 sampleVariance = glm::max(squares[i] / n - m * m, glm::dvec3(0.0)) * (n / (n - 1.0));
            variance.pixels()[i] = glm::vec3(sampleVariance / n);
        }
    }
    out.layers.emplace_back("", std::move(mean));
    for (std::uint32_t l = 0; l < shader::kPathLayerCount; ++l) {
        if ((mLayers & (1u << l)) == 0) continue;
        const std::vector<glm::dvec3> layer = downloadSums(ctx, mImage, shader::blAccumLayerSlot(mLayers, l));
        Image image(width, height);
        for (std::size_t i = 0; i < image.pixelCount(); ++i) {
            if (totals[i].w > 0.0f) image.pixels()[i] = glm::vec3(layer[i] / double(totals[i].w));
        }
        out.layers.emplace_back(kAccumLayerNames[l], std::move(image));
    }
    out.layers.emplace_back("variance", std::move(variance));
    return out;
}

} // namespace bl::gpu
