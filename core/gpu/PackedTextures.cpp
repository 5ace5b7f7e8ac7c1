#include "gpu/PackedTextures.h"

#include "base/Error.h"
#include "image/Image.h"

#include <shared/PackedTextures.h>

#include <bit>
#include <cstring>
#include <vector>

namespace bl::gpu {

std::uint64_t PackedTextures::words(const Scene& scene) {
    std::uint64_t n = shader::kPackedTexturesDecodeWords + shader::kPackedTexturesHeaderWords * scene.textures.size();
    for (const Texture& t : scene.textures) n += std::uint64_t(t.image.width) * std::uint64_t(t.image.height);
    return n;
}

PackedTextures::PackedTextures(const vk::Context& ctx, const Scene& scene) {
    const std::uint64_t count = words(scene);
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(ctx.physicalDevice(), &properties);
    const std::uint64_t range = properties.limits.maxStorageBufferRange;
    if (count * 4 > range) {
        throw Error("packed textures: the scene's " + std::to_string(scene.textures.size()) + " textures need " +
                    std::to_string(count * 4) + " bytes, more than one storage buffer binding of '" + ctx.info().name +
                    "' holds (" + std::to_string(range) + ")");
    }
    std::vector<std::uint32_t> packed(count, 0u);
    for (std::uint32_t i = 0; i < shader::kPackedTexturesDecodeWords; ++i) {
        packed[i] = std::bit_cast<std::uint32_t>(srgbToLinear(float(i) / 255.0f));
    }
    std::uint64_t next = shader::kPackedTexturesDecodeWords + shader::kPackedTexturesHeaderWords * scene.textures.size();
    for (std::size_t t = 0; t < scene.textures.size(); ++t) {
        const Rgba8Image& image = scene.textures[t].image;
        const std::uint64_t texels = std::uint64_t(image.width) * std::uint64_t(image.height);
        if (image.width <= 0 || image.height <= 0 || image.texels.size() != 4 * texels) {
            throw Error("packed textures: texture '" + scene.textures[t].path + "' has " + std::to_string(image.width) +
                        "x" + std::to_string(image.height) + " texels and " + std::to_string(image.texels.size()) +
                        " bytes");
        }
        std::uint32_t* header = &packed[shader::kPackedTexturesDecodeWords + shader::kPackedTexturesHeaderWords * t];
        header[0] = static_cast<std::uint32_t>(next);
        header[1] = static_cast<std::uint32_t>(image.width);
        header[2] = static_cast<std::uint32_t>(image.height);
        std::memcpy(&packed[next], image.texels.data(), image.texels.size()); // little-endian: r in the low byte
        next += texels;
    }
    mBuffer = vk::makeBuffer(ctx, std::span<const std::uint32_t>(packed), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
}

} // namespace bl::gpu
