#include "gpu/Accumulator.h"

#include "vk/Commands.h"

#include <algorithm>

namespace bl::gpu {

Accumulator::Accumulator(const vk::Context& ctx, std::uint32_t width, std::uint32_t height)
    : mImage(ctx, {width, height, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT}) {
    clear(ctx);
}

void Accumulator::clear(const vk::Context& ctx) {
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        vk::transitionImage(cmd, mImage.get(), vk::ImageTransition{});
        VkClearColorValue zero{};
        VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, mImage.get(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
    });
}

Image Accumulator::resolve(const vk::Context& ctx, std::uint32_t expected, std::uint64_t* missing) const {
    std::vector<std::byte> raw = mImage.download(ctx, VK_IMAGE_LAYOUT_GENERAL);
    const auto* sums = reinterpret_cast<const glm::vec4*>(raw.data());
    Image out(static_cast<int>(mImage.desc().width), static_cast<int>(mImage.desc().height));
    std::uint64_t lacking = 0;
    for (std::size_t i = 0; i < out.pixelCount(); ++i) {
        out.pixels()[i] = sums[i].w > 0.0f ? glm::vec3(sums[i]) / sums[i].w : glm::vec3(0.0f);
        lacking += static_cast<std::uint64_t>(expected - std::min(static_cast<std::uint32_t>(sums[i].w), expected));
    }
    if (missing) *missing = lacking;
    return out;
}

} // namespace bl::gpu
