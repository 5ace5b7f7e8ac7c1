#version 460
#extension GL_GOOGLE_include_directive : require
// Looks queries up in the packed texture buffer (gpu/PackedTextureLookup.glsl) so a test can compare
// them with the reference's bilinearLookup: query i = (u, v, texture index as float bits, unused),
// result i = the filtered linear RGB.
#define BL_PACKED_TEXTURES_SET 0
#define BL_PACKED_TEXTURES_BINDING 0
#include "gpu/PackedTextureLookup.glsl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 1) readonly buffer QueryBlock { vec4 queries[]; };
layout(set = 0, binding = 2) writeonly buffer ResultBlock { vec4 results[]; };
layout(push_constant) uniform PushBlock { uint count; } push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) {
        return;
    }
    vec4 q = queries[i];
    results[i] = vec4(blPackedTextureLookup(floatBitsToUint(q.z), q.xy), 0.0);
}
