// A progressive per-pixel estimate on the GPU, split by path length like the CPU reference
// (emitted, direct, indirect1, indirect2, rest), with a second moment for the variance of the mean.
// Shaders add samples through shaders/gpu/Accumulate.glsl; resolve() divides on the host.
//
// Storage: one rgba32f image array (slots of shaders/shared/Accumulation.h). An image rather than a
// buffer: one binding of a large frame would pass lavapipe's 128 MiB limit.
//
// Precision: every sum is compensated (Neumaier) in a second slot, not kept in double: the device
// layer does not enable shaderFloat64 (and many GPUs run it at 1/32 rate or emulate it), and 64-bit
// image formats are not storage formats anywhere. A compensated float sum of 10^5 samples stays
// within a few ulp of the exact one, where a plain float sum drifts by ~1e-4 relative.
//
// Samples that never arrive are counted in two kinds: non-finite ones (a shader computed NaN/Inf and
// the sample was refused, counted per pixel) and dropped ones (the mode added nothing for that pixel,
// e.g. a point outside every bundle frame): the rest of the shortfall against `expected`.
#pragma once

#include "image/Image.h"
#include "vk/GpuImage.h"

#include <array>
#include <shared/Accumulation.h>
#include <string>
#include <utility>
#include <vector>

namespace bl::gpu {

// Layer names of ImageSets, in shader::kPath* order; the same as the CPU reference's
// kPathLayerNames (tests/core/gpu/AccumulatorTest.cpp checks it).
inline constexpr std::array<const char*, shader::kPathLayerCount> kAccumLayerNames = {
    "emitted", "direct", "indirect1", "indirect2", "rest"};

struct AccumulatedImages {
    // "" (the mean of all written layers), then each written layer by name, then "variance" (the
    // per-pixel variance of the mean, per channel; 0 below two samples).
    std::vector<std::pair<std::string, Image>> layers;
    std::uint64_t nonFiniteSamples = 0; // refused as NaN/Inf, summed over pixels
    std::uint64_t droppedSamples = 0;   // never added, summed over pixels
    std::uint64_t expectedSamples = 0;  // samples per pixel asked for x pixels: what the two are parts of
};

class Accumulator {
public:
    Accumulator() = default;
    // `layers`: bit l set = the mode writes path layer l (shader::kPath*), the BL_ACCUM_LAYERS
    // its shader uses. Submits and waits once (the initial clear).
    Accumulator(const vk::Context& ctx, std::uint32_t width, std::uint32_t height, std::uint32_t layers);

    // Device memory per pixel for a layer mask.
    static VkDeviceSize bytesPerPixel(std::uint32_t layers);

    // Zeroes the sums and leaves the image in VK_IMAGE_LAYOUT_GENERAL: submitting and waiting, or
    // recorded into the mode's command buffer (a new frame of an animation).
    void clear(const vk::Context& ctx);
    void recordClear(VkCommandBuffer cmd) const;

    VkImageView view() const { return mImage.view(); }
    std::uint32_t layers() const { return mLayers; }

    // Means, layers, variance and the two shortfall counts, given that every pixel should have
    // received `expected` samples.
    AccumulatedImages resolve(const vk::Context& ctx, std::uint32_t expected) const;

private:
    std::uint32_t mLayers = 0;
    vk::GpuImage mImage;
};

} // namespace bl::gpu
