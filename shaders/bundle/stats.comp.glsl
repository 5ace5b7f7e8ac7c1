#version 460
#extension GL_GOOGLE_include_directive : require
// Per-bundle statistics: non-empty pixels, longest list, fragments reachable from the heads.
#include "bundle/BundleBuffers.glsl"
#extension GL_KHR_shader_subgroup_arithmetic : require

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform FrameBlock { BundleFrame frame; };
layout(set = 0, binding = 2) buffer StatsBlock { uint nonEmpty; uint longest; uint reachable; uint pad; };
layout(push_constant) uniform PushBlock { BundleBuildPush push; };

void main() {
    uint pixel = gl_GlobalInvocationID.x;
    uint length = 0u;
    if (pixel < frame.width * frame.height) {
        BundleNodes nodes = BundleNodes(push.nodeAddress);
        uint i = BundleHeads(push.headAddress).heads[pixel] & kBundleIndexMask;
        while (i != kBundleNil) {
            length += 1u;
            i = nodes.nodes[i].next & kBundleIndexMask;
        }
    }
    // One atomic per subgroup, not per pixel: the walk, not the bookkeeping, is what is timed.
    uint filled = subgroupAdd(length > 0u ? 1u : 0u);
    uint most = subgroupMax(length);
    uint total = subgroupAdd(length);
    if (subgroupElect()) {
        atomicAdd(nonEmpty, filled);
        atomicMax(longest, most);
        atomicAdd(reachable, total);
    }
}
