// A 2D (array) image with its own memory, a view of all layers and one view per layer (for
// rendering into a single layer, e.g. a shadow-cube face).
#pragma once

#include "vk/Context.h"

#include <vector>

namespace bl::vk {

class Buffer;

struct GpuImageDesc {
    std::uint32_t width = 1;
    std::uint32_t height = 1;
    std::uint32_t layers = 1;
    VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT;
    VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT;
    bool arrayView = false; // view all layers as a 2D array even when layers == 1
};

class GpuImage {
public:
    GpuImage() = default;
    GpuImage(const Context& ctx, const GpuImageDesc& desc);

    VkImage get() const { return mImage.get(); }
    VkImageView view() const { return mView.get(); }
    VkImageView layerView(std::uint32_t layer) const { return mLayerViews[layer].get(); }
    const GpuImageDesc& desc() const { return mDesc; }
    VkImageAspectFlags aspect() const;

    // Fills layer 0 from tightly packed texels (bytes per texel implied by the format) and leaves
    // the image in SHADER_READ_ONLY_OPTIMAL.
    void upload(const Context& ctx, const void* texels, VkDeviceSize bytes);
    // Copies one layer, currently in `layout`, back to the host; the layout is kept.
    std::vector<std::byte> download(const Context& ctx, VkImageLayout layout, std::uint32_t layer = 0) const;
    // The same copy into a caller's readback buffer of at least width * height texels (kept across
    // calls by those that read back every frame: no staging allocation per call).
    void downloadInto(const Context& ctx, VkImageLayout layout, const Buffer& readback, std::uint32_t layer = 0) const;

private:
    GpuImageDesc mDesc;
    ImageHandle mImage;
    Memory mMemory;
    ImageView mView;
    std::vector<ImageView> mLayerViews;
};

std::uint32_t bytesPerTexel(VkFormat format);

Sampler makeSampler(VkDevice device, VkFilter filter, VkSamplerAddressMode addressU,
                    VkSamplerAddressMode addressV);

} // namespace bl::vk
