// Bilinear albedo lookups in the packed texture buffer (shaders/shared/PackedTextures.h,
// core/gpu/PackedTextures.h): repeat wrap, texel centres at (i + 1/2) / size, texels decoded from
// sRGB before filtering, exactly the reference's bilinearLookup (core/image/BilinearLookup.h).
// Define BL_PACKED_TEXTURES_SET and BL_PACKED_TEXTURES_BINDING before including, and
// BL_ALBEDO_TEXTURES where a specialization constant says whether any material has a texture
// (gpu/MaterialSpecialization.glsl).
#ifndef BL_GPU_PACKED_TEXTURE_LOOKUP_GLSL
#define BL_GPU_PACKED_TEXTURE_LOOKUP_GLSL
#ifndef BL_ALBEDO_TEXTURES
#define BL_ALBEDO_TEXTURES true
#endif
#include "shared/GpuTypes.h"
#include "shared/PackedTextures.h"

layout(set = BL_PACKED_TEXTURES_SET, binding = BL_PACKED_TEXTURES_BINDING) readonly buffer PackedTextureBlock {
    uint packedTextures[];
};

vec3 blPackedTexel(uint first, int width, int height, int x, int y) {
    x = ((x % width) + width) % width;
    y = ((y % height) + height) % height;
    uint t = packedTextures[first + uint(y * width + x)];
    return vec3(uintBitsToFloat(packedTextures[t & 0xffu]), uintBitsToFloat(packedTextures[(t >> 8u) & 0xffu]),
                uintBitsToFloat(packedTextures[(t >> 16u) & 0xffu]));
}

// Texture `index` at uv (u = 0 left edge, v = 0 top edge; OBJ coordinates need v -> 1 - v).
// Non-finite coordinates read texel 0.
vec3 blPackedTextureLookup(uint index, vec2 uv) {
    uint header = kPackedTexturesDecodeWords + kPackedTexturesHeaderWords * index;
    uint first = packedTextures[header];
    int width = int(packedTextures[header + 1u]), height = int(packedTextures[header + 2u]);
    if (any(isnan(uv)) || any(isinf(uv))) {
        return blPackedTexel(first, width, height, 0, 0);
    }
    vec2 f = (uv - floor(uv)) * vec2(width, height) - 0.5;
    vec2 f0 = floor(f);
    vec2 t = f - f0;
    int x0 = int(f0.x), y0 = int(f0.y);
    vec3 top = mix(blPackedTexel(first, width, height, x0, y0), blPackedTexel(first, width, height, x0 + 1, y0), t.x);
    vec3 bottom =
        mix(blPackedTexel(first, width, height, x0, y0 + 1), blPackedTexel(first, width, height, x0 + 1, y0 + 1), t.x);
    return mix(top, bottom, t.y);
}

// Albedo of material m at OBJ texture coordinates uv (v = 0 at the bottom; image row 0 is the top):
// its texture where it has one, else its constant albedo.
vec3 blPackedTextureAlbedo(GpuMaterial m, vec2 uv) {
    if (!BL_ALBEDO_TEXTURES || m.albedoTexture == kNoTexture) {
        return m.albedo;
    }
    return blPackedTextureLookup(m.albedoTexture, vec2(uv.x, 1.0 - uv.y));
}
#endif
