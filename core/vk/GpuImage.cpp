#include "vk/GpuImage.h"

#include "base/Error.h"
#include "vk/Buffer.h"
#include "vk/Check.h"
#include "vk/Commands.h"

namespace bl::vk {

std::uint32_t bytesPerTexel(VkFormat format) {
    switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_D32_SFLOAT:
        return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_UINT:
        return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
        return 16;
    default:
        throw Error("bytesPerTexel: unsupported format " + std::to_string(static_cast<int>(format)));
    }
}

VkImageAspectFlags GpuImage::aspect() const {
    return mDesc.format == VK_FORMAT_D32_SFLOAT ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

GpuImage::GpuImage(const Context& ctx, const GpuImageDesc& desc) : mDesc(desc) {
    const VkPhysicalDeviceLimits& limits = ctx.limits();
    if (desc.width == 0 || desc.height == 0 || desc.width > limits.maxImageDimension2D ||
        desc.height > limits.maxImageDimension2D || desc.layers == 0 ||
        desc.layers > limits.maxImageArrayLayers) {
        throw Error("GpuImage: size " + std::to_string(desc.width) + "x" + std::to_string(desc.height) + "x" +
                    std::to_string(desc.layers) + " outside the device limits (" +
                    std::to_string(limits.maxImageDimension2D) + " per side, " +
                    std::to_string(limits.maxImageArrayLayers) + " layers)");
    }
    VkDevice device = ctx.device();
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = desc.format;
    info.extent = {desc.width, desc.height, 1};
    info.mipLevels = 1;
    info.arrayLayers = desc.layers;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = desc.usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage raw = VK_NULL_HANDLE;
    BL_VK_CHECK(vkCreateImage(device, &info, nullptr, &raw));
    mImage = ImageHandle(device, raw);

    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, raw, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &mem);
    alloc.memoryTypeIndex = chooseMemoryType(mem, req.memoryTypeBits, MemoryUse::Device, req.size);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    BL_VK_CHECK(vkAllocateMemory(device, &alloc, nullptr, &memory));
    mMemory = Memory(device, memory);
    BL_VK_CHECK(vkBindImageMemory(device, raw, memory, 0));

    auto makeView = [&](VkImageViewType type, std::uint32_t base, std::uint32_t count) {
        VkImageViewCreateInfo v{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        v.image = raw;
        v.viewType = type;
        v.format = desc.format;
        v.subresourceRange = {aspect(), 0, 1, base, count};
        VkImageView view = VK_NULL_HANDLE;
        BL_VK_CHECK(vkCreateImageView(device, &v, nullptr, &view));
        return ImageView(device, view);
    };
    bool array = desc.arrayView || desc.layers > 1;
    mView = makeView(array ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D, 0, desc.layers);
    if (array) { // every layer its own 2D view too (an attachment is one layer)
        for (std::uint32_t l = 0; l < desc.layers; ++l) {
            mLayerViews.push_back(makeView(VK_IMAGE_VIEW_TYPE_2D, l, 1));
        }
    }
}

void GpuImage::upload(const Context& ctx, const void* texels, VkDeviceSize bytes) {
    const VkDeviceSize expected = VkDeviceSize(mDesc.width) * mDesc.height * bytesPerTexel(mDesc.format);
    if (bytes != expected) {
        throw Error("GpuImage::upload: " + std::to_string(bytes) + " bytes for an image of " +
                    std::to_string(expected));
    }
    Buffer staging(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload);
    std::memcpy(staging.data(), texels, bytes);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        ImageTransition toDst;
        toDst.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        toDst.aspect = aspect();
        transitionImage(cmd, get(), toDst);
        VkBufferImageCopy region{};
        region.imageSubresource = {aspect(), 0, 0, 1};
        region.imageExtent = {mDesc.width, mDesc.height, 1};
        vkCmdCopyBufferToImage(cmd, staging.get(), get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        ImageTransition toRead;
        toRead.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        toRead.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        toRead.aspect = aspect();
        transitionImage(cmd, get(), toRead);
    });
}

std::vector<std::byte> GpuImage::download(const Context& ctx, VkImageLayout layout, std::uint32_t layer) const {
    const VkDeviceSize bytes = VkDeviceSize(mDesc.width) * mDesc.height * bytesPerTexel(mDesc.format);
    Buffer staging(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    downloadInto(ctx, layout, staging, layer);
    std::vector<std::byte> out(bytes);
    std::memcpy(out.data(), staging.data(), bytes);
    return out;
}

void GpuImage::downloadInto(const Context& ctx, VkImageLayout layout, const Buffer& staging, std::uint32_t layer) const {
    const VkDeviceSize bytes = VkDeviceSize(mDesc.width) * mDesc.height * bytesPerTexel(mDesc.format);
    if (staging.size() < bytes) {
        throw Error("image download: a readback buffer of " + std::to_string(staging.size()) + " bytes for " +
                    std::to_string(bytes));
    }
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        ImageTransition toSrc;
        toSrc.oldLayout = layout;
        toSrc.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        toSrc.aspect = aspect();
        toSrc.baseLayer = layer;
        toSrc.layerCount = 1;
        transitionImage(cmd, get(), toSrc);
        VkBufferImageCopy region{};
        region.imageSubresource = {aspect(), 0, layer, 1};
        region.imageExtent = {mDesc.width, mDesc.height, 1};
        vkCmdCopyImageToBuffer(cmd, get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.get(), 1, &region);
        ImageTransition back = toSrc;
        back.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        back.newLayout = layout;
        transitionImage(cmd, get(), back);
        // The fence alone does not make device writes visible to host reads.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_HOST_BIT);
    });
}

Sampler makeSampler(VkDevice device, VkFilter filter, VkSamplerAddressMode addressU,
                    VkSamplerAddressMode addressV) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = filter;
    info.minFilter = filter;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = addressU;
    info.addressModeV = addressV;
    info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.maxLod = 0.0f;
    VkSampler raw = VK_NULL_HANDLE;
    BL_VK_CHECK(vkCreateSampler(device, &info, nullptr, &raw));
    return Sampler(device, raw);
}

} // namespace bl::vk
