#version 460
#extension GL_GOOGLE_include_directive : require
// Per-bundle statistics: non-empty pixels, longest list, fragments reachable from the heads.
#include "bundle/BundleBuffers.glsl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform FrameBlock { BundleFrame frame; };
layout(set = 0, binding = 2) buffer StatsBlock { uint nonEmpty; uint longest; uint reachable; uint pad; };
layout(push_constant) uniform PushBlock { BundleBuildPush push; };

void main() {
    uint pixel = gl_GlobalInvocationID.x;
    if (pixel >= frame.width * frame.height) {
        return;
    }
    BundleNodes nodes = BundleNodes(push.nodeAddress);
    uint length = 0u;
    uint i = BundleHeads(push.headAddress).heads[pixel] & kBundleIndexMask;
    while (i != kBundleNil) {
        length += 1u;
        i = nodes.nodes[i].next & kBundleIndexMask;
    }
    if (length > 0u) {
        atomicAdd(nonEmpty, 1u);
        atomicMax(longest, length);
        atomicAdd(reachable, length);
    }
}
