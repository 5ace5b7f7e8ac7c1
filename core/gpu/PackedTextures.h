// A scene's albedo textures packed into one storage buffer (layout: shaders/shared/PackedTextures.h;
// lookups: shaders/gpu/PackedTextureLookup.glsl), so a compute pass can read any material's texture
// through a single binding, with no descriptor indexing (which the core device does not enable).
// Texels stay RGBA8 sRGB (4 bytes each) and are decoded by a table of the reference's exact
// srgbToLinear. A scene whose textures need more than one binding holds (lavapipe: 128 MiB) is
// refused with the sizes; a scene without textures gets the decode table only.
#pragma once

#include "scene/Scene.h"
#include "vk/Buffer.h"

namespace bl::gpu {

class PackedTextures {
public:
    PackedTextures(const vk::Context& ctx, const Scene& scene);

    // Words the scene's textures need (table, headers, texels).
    static std::uint64_t words(const Scene& scene);

    VkBuffer buffer() const { return mBuffer.get(); }
    VkDeviceSize bytes() const { return mBuffer.size(); }

private:
    vk::Buffer mBuffer;
};

} // namespace bl::gpu
