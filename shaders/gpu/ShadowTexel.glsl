// One texel of a shadow cube (core/gpu/ShadowCubePass.h), rgba16ui: the distance from the cube's
// centre to the nearest surface along the texel's centre ray as float bits (low half, high half;
// +inf where nothing), then that surface's shading normal (either sign), octahedral (low half, high
// half), or kShadowNoNormal where it has none. In memory (little-endian) a float and a uint. The
// normal is what the lookup needs to keep a closed room's creases dark (ShadowCubeLookup.glsl).
#ifndef BL_GPU_SHADOW_TEXEL_GLSL
#define BL_GPU_SHADOW_TEXEL_GLSL
#include "shared/Octahedral.h"

// A packing blPackOctahedral never produces: packSnorm2x16 writes -1 as -32767 (0x8001), never
// 0x8000.
const uint kShadowNoNormal = 0x80008000u;

uvec4 blPackShadowTexel(float distance, vec3 normal) {
    uint d = floatBitsToUint(distance);
    float lengthSquared = dot(normal, normal);
    uint n = lengthSquared > 1e-30 ? blPackOctahedral(normal * inversesqrt(lengthSquared)) : kShadowNoNormal;
    return uvec4(d & 0xffffu, d >> 16, n & 0xffffu, n >> 16);
}

float blShadowTexelDistance(uvec4 texel) { return uintBitsToFloat(texel.x | (texel.y << 16)); }

// The texel's surface normal; false where it has none.
bool blShadowTexelNormal(uvec4 texel, out vec3 normal) {
    uint packed = texel.z | (texel.w << 16);
    normal = packed == kShadowNoNormal ? vec3(0.0) : blUnpackOctahedral(packed);
    return packed != kShadowNoNormal;
}

#endif
