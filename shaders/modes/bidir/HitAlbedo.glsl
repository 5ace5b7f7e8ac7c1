// Mode bidir: albedo at a bundle hit y with its texture (the hit payload's interpolated UV, looked
// up bilinearly in the packed texture buffer as the reference does, gpu/PackedTextureLookup.glsl);
// VPLs from reflective shadow maps carry their textured albedo from the RSM's G-buffer already.
#include "modes/bidir/BidirTextures.h"
#define BL_PACKED_TEXTURES_SET kBidirSet
#define BL_PACKED_TEXTURES_BINDING kBidirBindingTextures
#include "gpu/PackedTextureLookup.glsl"

vec3 bidirHitAlbedo(GpuMaterial m, vec2 uv) {
    if (m.albedoTexture == kNoTexture) {
        return m.albedo;
    }
    // OBJ texture coordinates have v = 0 at the bottom; image row 0 is the top.
    return blPackedTextureLookup(m.albedoTexture, vec2(uv.x, 1.0 - uv.y));
}
