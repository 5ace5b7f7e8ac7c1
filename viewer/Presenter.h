// Shows CPU-made frames (8-bit sRGB RGBA, row 0 at the top) in a window's Vulkan surface: a
// swapchain whose images are filled by a buffer copy, so any Vulkan 1.3 device that can present
// works, lavapipe included (no graphics pipeline of its own). Recreated when the surface changes.
#pragma once

#include "vk/Buffer.h"
#include "vk/Context.h"

#include <cstdint>
#include <vector>

namespace bl::viewer {

class Presenter {
public:
    // Takes ownership of `surface`; throws when the context's queue cannot present to it.
    Presenter(const vk::Context& ctx, VkSurfaceKHR surface, std::uint32_t width, std::uint32_t height);
    ~Presenter();
    Presenter(const Presenter&) = delete;
    Presenter& operator=(const Presenter&) = delete;

    // Presents `rgba` (width x height x 4 bytes, sRGB-encoded); a frame of another size than the
    // swapchain's is cropped or padded with black at the right and bottom.
    void present(const std::vector<unsigned char>& rgba, std::uint32_t width, std::uint32_t height);

private:
    void createSwapchain(std::uint32_t width, std::uint32_t height);
    void destroySwapchain();

    const vk::Context* mContext;
    VkSurfaceKHR mSurface = VK_NULL_HANDLE;
    VkSwapchainKHR mSwapchain = VK_NULL_HANDLE;
    VkFormat mFormat = VK_FORMAT_UNDEFINED;
    VkExtent2D mExtent{};
    std::vector<VkImage> mImages;
    VkFence mAcquired = VK_NULL_HANDLE;
    vk::Buffer mStaging;
};

} // namespace bl::viewer
