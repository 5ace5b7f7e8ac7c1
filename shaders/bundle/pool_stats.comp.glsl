#version 460
#extension GL_GOOGLE_include_directive : require
// Statistics of one pool slot: non-empty pixels, longest list, nodes reachable from the heads.
// Walking every list once is also the traversal benchmark.
#include "bundle/BundleBuffers.glsl"
#extension GL_KHR_shader_subgroup_arithmetic : require

layout(local_size_x = kBundleSortGroupSize) in;
layout(push_constant) uniform PushBlock { BundlePoolPush push; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer StatsBlock { BundleListStats stats; };

void main() {
    BundleFrame frame = blBundlePoolFrame(push.pool, push.slot);
    uint pixel = gl_GlobalInvocationID.x;
    uint length = 0u;
    if (pixel < frame.width * frame.height) {
        BundleNodes nodes = BundleNodes(push.pool.nodes);
        uint i = blBundlePoolHeads(push.pool, push.slot).heads[pixel] & kBundleIndexMask;
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
        StatsBlock block = StatsBlock(push.statsAddress);
        atomicAdd(block.stats.nonEmptyPixels, filled);
        atomicMax(block.stats.longestList, most);
        atomicAdd(block.stats.reachableNodes, total);
    }
}
