#version 460
#extension GL_GOOGLE_include_directive : require
// Mode bidir: VPL sampling from a reflective shadow map on the GPU ([TO12] section 4.1,
// shaders/modes/bidir/Rsm.h). One invocation per pair k: it draws the light uniformly and a texel
// of that light's cube by its flux CDF (binary search over the 32-bit fixed-point starts), and,
// when the texel lies on the face just rendered (this dispatch's light and face), gathers what
// the face's G-buffer holds there. The host completes each VPL's record (densities, intensity).
#include "modes/bidir/Rsm.h"

layout(local_size_x = kBidirRsmGroupSize) in;

layout(binding = kBidirRsmBindingPosition, rgba32f) readonly uniform image2D rsmPosition;
layout(binding = kBidirRsmBindingNormal, rgba32f) readonly uniform image2D rsmNormal;
layout(binding = kBidirRsmBindingAlbedo, rgba32f) readonly uniform image2D rsmAlbedo;
layout(binding = kBidirRsmBindingCdf) readonly buffer CdfBlock { uint header[kBidirRsmHeaderWords]; uint start[]; };
layout(binding = kBidirRsmBindingTexels) buffer TexelBlock { BidirRsmTexel texels[]; };
layout(push_constant) uniform PushBlock { BidirRsmPush push; };

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= push.pairs) {
        return;
    }
    uint index = push.first + k;
    // The source: uniform among push.lightCount (the L lights, and the area emitters as source L,
    // which no dispatch's light matches: the host traces those pairs), from the top bits of a
    // 32-bit draw (ReflectiveShadowMap.cpp repeats it on the host).
    float uLight = float(blRsmRandom(push.key, index, 0u) >> 8u) * (1.0 / 16777216.0);
    uint l = min(uint(uLight * float(push.lightCount)), push.lightCount - 1u);
    if (l != push.light) {
        return;
    }
    uint n = push.resolution;
    uint texelsPerLight = 6u * n * n;
    uint base = l * texelsPerLight;
    uint u = blRsmRandom(push.key, index, 1u);
    // The largest t with start[t] <= u (start[0] = 0).
    uint lo = 0u, hi = texelsPerLight - 1u;
    while (lo < hi) {
        uint mid = (lo + hi + 1u) / 2u;
        if (start[base + mid] <= u) {
            lo = mid;
        } else {
            hi = mid - 1u;
        }
    }
    uint t = lo;
    if (t / (n * n) != push.face) {
        return;
    }
    uint inFace = t % (n * n);
    ivec2 texel = ivec2(inFace % n, inFace / n);
    texels[k].position = imageLoad(rsmPosition, texel);
    texels[k].normal = imageLoad(rsmNormal, texel);
    texels[k].albedo = imageLoad(rsmAlbedo, texel);
    texels[k].light = l;
    texels[k].texel = t;
    texels[k].written = 1u;
}
