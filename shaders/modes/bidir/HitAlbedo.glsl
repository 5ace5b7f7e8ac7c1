// Mode bidir: albedo at a bundle hit y with its texture (blPackedTextureAlbedo at the hit payload's
// interpolated UV, bilinear in the packed texture buffer as the reference does);
// VPLs from reflective shadow maps carry their textured albedo from the RSM's G-buffer already.
#include "modes/bidir/BidirTextures.h"
#define BL_PACKED_TEXTURES_SET kBidirSet
#define BL_PACKED_TEXTURES_BINDING kBidirBindingTextures
#include "gpu/PackedTextureLookup.glsl"
