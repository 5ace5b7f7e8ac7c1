#include "viewer/Presenter.h"

#include "base/Error.h"
#include "vk/Check.h"

#include <algorithm>
#include <cstring>

namespace bl::viewer {

Presenter::Presenter(const vk::Context& ctx, VkSurfaceKHR surface, std::uint32_t width, std::uint32_t height)
    : mContext(&ctx), mSurface(surface) {
    VkBool32 supported = VK_FALSE;
    vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physicalDevice(), ctx.queueFamily(), surface, &supported);
    if (!supported) {
        vkDestroySurfaceKHR(ctx.instance(), surface, nullptr);
        throw Error("bundlelab view: " + ctx.info().name + " cannot present to this window (pick another --device)");
    }
    try {
        VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        BL_VK_CHECK(vkCreateFence(ctx.device(), &fenceInfo, nullptr, &mAcquired));
        createSwapchain(width, height);
    } catch (...) {
        destroySwapchain();
        if (mAcquired) vkDestroyFence(ctx.device(), mAcquired, nullptr);
        vkDestroySurfaceKHR(ctx.instance(), surface, nullptr);
        throw;
    }
}

Presenter::~Presenter() {
    vkDeviceWaitIdle(mContext->device());
    destroySwapchain();
    if (mAcquired) vkDestroyFence(mContext->device(), mAcquired, nullptr);
    vkDestroySurfaceKHR(mContext->instance(), mSurface, nullptr);
}

void Presenter::destroySwapchain() {
    if (mSwapchain) vkDestroySwapchainKHR(mContext->device(), mSwapchain, nullptr);
    mSwapchain = VK_NULL_HANDLE;
    mImages.clear();
}

void Presenter::createSwapchain(std::uint32_t width, std::uint32_t height) {
    VkPhysicalDevice physical = mContext->physicalDevice();
    VkSurfaceCapabilitiesKHR caps{};
    BL_VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, mSurface, &caps));
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT)) {
        throw Error("bundlelab view: the surface's images cannot be written by a copy (no TRANSFER_DST usage)");
    }
    std::uint32_t n = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical, mSurface, &n, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(n);
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical, mSurface, &n, formats.data());
    // 8-bit UNORM, its bytes the sRGB-encoded frame as they are (no second encoding).
    const auto chosen = std::find_if(formats.begin(), formats.end(), [](const VkSurfaceFormatKHR& f) {
        return f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM;
    });
    if (chosen == formats.end()) throw Error("bundlelab view: the surface offers no 8-bit UNORM RGBA/BGRA format");
    mFormat = chosen->format;
    // The surface's size, or (where it follows the swapchain, as on Wayland) the frame's, within
    // the surface's limits. A minimised window has no size: nothing is made, nothing is shown.
    mExtent = caps.currentExtent.width != UINT32_MAX
                  ? caps.currentExtent
                  : VkExtent2D{std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width),
                               std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height)};
    if (mExtent.width == 0 || mExtent.height == 0) return;
    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = mSurface;
    info.minImageCount = std::max(caps.minImageCount, 2u);
    if (caps.maxImageCount) info.minImageCount = std::min(info.minImageCount, caps.maxImageCount);
    info.imageFormat = chosen->format;
    info.imageColorSpace = chosen->colorSpace;
    info.imageExtent = mExtent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR; // always supported
    info.clipped = VK_TRUE;
    BL_VK_CHECK(vkCreateSwapchainKHR(mContext->device(), &info, nullptr, &mSwapchain));
    vkGetSwapchainImagesKHR(mContext->device(), mSwapchain, &n, nullptr);
    mImages.resize(n);
    vkGetSwapchainImagesKHR(mContext->device(), mSwapchain, &n, mImages.data());
    mStaging = vk::Buffer(*mContext, VkDeviceSize(mExtent.width) * mExtent.height * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                          vk::MemoryUse::Upload);
}

void Presenter::present(const std::vector<unsigned char>& rgba, std::uint32_t width, std::uint32_t height) {
    VkDevice device = mContext->device();
    if (!mSwapchain) { // minimised: try again, show nothing until the window has a size
        createSwapchain(width, height);
        if (!mSwapchain) return;
    }
    std::uint32_t index = 0;
    VkResult r = vkAcquireNextImageKHR(device, mSwapchain, UINT64_MAX, VK_NULL_HANDLE, mAcquired, &index);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
        vkDeviceWaitIdle(device);
        destroySwapchain();
        createSwapchain(width, height);
        return; // the next frame goes to the new swapchain
    }
    if (r != VK_SUCCESS && r != VK_SUBOPTIMAL_KHR) BL_VK_CHECK(r);
    BL_VK_CHECK(vkWaitForFences(device, 1, &mAcquired, VK_TRUE, UINT64_MAX));
    BL_VK_CHECK(vkResetFences(device, 1, &mAcquired));

    // The frame into the staging buffer in the swapchain's byte order, cropped or padded.
    auto* out = static_cast<unsigned char*>(mStaging.data());
    const bool bgra = mFormat == VK_FORMAT_B8G8R8A8_UNORM;
    for (std::uint32_t y = 0; y < mExtent.height; ++y) {
        for (std::uint32_t x = 0; x < mExtent.width; ++x) {
            unsigned char* o = out + (std::size_t(y) * mExtent.width + x) * 4;
            if (x < width && y < height) {
                const unsigned char* i = rgba.data() + (std::size_t(y) * width + x) * 4;
                o[0] = bgra ? i[2] : i[0];
                o[1] = i[1];
                o[2] = bgra ? i[0] : i[2];
                o[3] = 255;
            } else {
                std::memset(o, 0, 3);
                o[3] = 255;
            }
        }
    }
    const VkImage image = mImages[index];
    mContext->submitAndWait([&](VkCommandBuffer cmd) {
        VkImageMemoryBarrier toCopy{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        toCopy.srcAccessMask = 0;
        toCopy.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        toCopy.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        toCopy.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        toCopy.srcQueueFamilyIndex = toCopy.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        toCopy.image = image;
        toCopy.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                             nullptr, 1, &toCopy);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {mExtent.width, mExtent.height, 1};
        vkCmdCopyBufferToImage(cmd, mStaging.get(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        VkImageMemoryBarrier toPresent = toCopy;
        toPresent.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        toPresent.dstAccessMask = 0;
        toPresent.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        toPresent.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0, nullptr, 0,
                             nullptr, 1, &toPresent);
    });
    // The copy finished inside submitAndWait: the present waits on nothing.
    VkPresentInfoKHR presentInfo{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    presentInfo.swapchainCount = 1;
    presentInfo.pSwapchains = &mSwapchain;
    presentInfo.pImageIndices = &index;
    r = vkQueuePresentKHR(mContext->queue(), &presentInfo);
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) {
        vkDeviceWaitIdle(device);
        destroySwapchain();
        createSwapchain(width, height);
    } else if (r != VK_SUCCESS) {
        BL_VK_CHECK(r);
    }
}

} // namespace bl::viewer
