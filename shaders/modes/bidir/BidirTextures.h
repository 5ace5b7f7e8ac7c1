// Mode bidir's evaluation pass, set 1 (BidirShared.h): the scene's albedo textures packed in one
// buffer (core/gpu/PackedTextures.h), for textured albedo at bundle hits (HitAlbedo.glsl).
#ifndef BL_BIDIR_TEXTURES_H
#define BL_BIDIR_TEXTURES_H
#include "../../shared/Prelude.h"

BL_NAMESPACE_BEGIN
BL_CONST uint kBidirBindingTextures = 11u;
BL_NAMESPACE_END
#endif
