// A progressive per-pixel estimate on the GPU: an rgba32f storage image holding the running sum
// of radiance (rgb) and the number of samples added (a). Shaders add to it; resolve() divides.
// An image rather than a buffer: one binding of a large frame would pass lavapipe's 128 MiB limit.
// A sample a shader refuses (NaN/Inf) simply does not add to the count, so it is never averaged in.
#pragma once

#include "image/Image.h"
#include "vk/GpuImage.h"

namespace bl::gpu {

class Accumulator {
public:
    static constexpr VkDeviceSize kBytesPerPixel = 16; // rgba32f

    Accumulator() = default;
    Accumulator(const vk::Context& ctx, std::uint32_t width, std::uint32_t height);

    // Zeroes the sums and leaves the image in VK_IMAGE_LAYOUT_GENERAL (submits and waits).
    void clear(const vk::Context& ctx);
    VkImageView view() const { return mImage.view(); }

    // The mean per pixel (0 where no sample arrived); `missing` gets, summed over pixels, how many
    // of `expected` samples each pixel lacks.
    Image resolve(const vk::Context& ctx, std::uint32_t expected, std::uint64_t* missing = nullptr) const;

private:
    vk::GpuImage mImage;
};

} // namespace bl::gpu
