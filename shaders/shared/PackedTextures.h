// Every albedo texture of a scene in one storage buffer of 32-bit words (core/gpu/PackedTextures.h),
// for passes that cannot index an array of samplers (the core device does not enable descriptor
// indexing). Layout, shared C++/GLSL:
//   words [0, 256)            linear value of each sRGB byte (float bits): the decode table
//   words [256 + 4 t, +4)     texture t: first texel word, width, height, 0
//   texel words               RGBA8 as on disk (sRGB), row 0 at the top, r in the low byte
// Lookups (shaders/gpu/PackedTextureLookup.glsl) decode then filter bilinearly, as an sRGB sampler
// and the reference (core/image/BilinearLookup.h) do.
#ifndef BL_SHARED_PACKED_TEXTURES_H
#define BL_SHARED_PACKED_TEXTURES_H
#include "Prelude.h"

BL_NAMESPACE_BEGIN

BL_CONST uint kPackedTexturesDecodeWords = 256u;
BL_CONST uint kPackedTexturesHeaderWords = 4u;

BL_NAMESPACE_END
#endif
