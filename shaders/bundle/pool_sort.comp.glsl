#version 460
#extension GL_GOOGLE_include_directive : require
// Orders every list of pool slot push.slot + gl_WorkGroupID.y (one dispatch sorts consecutive slots) by depth along omega (nearest to the frame's origin plane
// first), keeping each node's face bit, and records each node's predecessor: afterwards a walk
// steps to the neighbour on either side in O(1) (Traversal.glsl: blBundleSortedNext/Previous).
// Nodes stay where the build put them; only the links change. Ties (coplanar duplicates) are
// ordered by node index, so a sorted list is a strict order.
#include "bundle/BundleBuffers.glsl"

layout(local_size_x = kBundleSortGroupSize) in;
layout(push_constant) uniform PushBlock { BundlePoolPush push; };

bool before(float depthA, uint a, float depthB, uint b) { return depthA < depthB || (depthA == depthB && a < b); }

void main() {
    uint slot = push.slot + gl_WorkGroupID.y;
    BundleFrame frame = blBundlePoolFrame(push.pool, slot);
    uint pixel = gl_GlobalInvocationID.x;
    if (pixel >= frame.width * frame.height) {
        return;
    }
    BundleHeads heads = blBundlePoolHeads(push.pool, slot);
    BundleNodes nodes = BundleNodes(push.pool.nodes);
    uint head = heads.heads[pixel] & kBundleIndexMask;

    float depths[kBundleSortLocalNodes];
    uint order[kBundleSortLocalNodes];
    uint count = 0u;
    bool fits = true;
    for (uint i = head; i != kBundleNil; i = nodes.nodes[i].next & kBundleIndexMask) {
        if (count == kBundleSortLocalNodes) {
            fits = false;
            break;
        }
        // Insertion into the local array: lists are short, and this keeps it in registers.
        float d = nodes.nodes[i].depth;
        uint k = count;
        while (k > 0u && before(d, i, depths[k - 1u], order[k - 1u])) {
            depths[k] = depths[k - 1u];
            order[k] = order[k - 1u];
            --k;
        }
        depths[k] = d;
        order[k] = i;
        ++count;
    }
    if (fits) {
        uint next = kBundleNil;
        for (uint k = count; k > 0u; --k) {
            uint i = order[k - 1u];
            nodes.nodes[i].next = next | (nodes.nodes[i].next & kBundleFrontFaceBit);
            next = i;
        }
        heads.heads[pixel] = next;
    } else {
        // A long list: insertion sort of the linked list itself (quadratic, rare, equally exact).
        uint sorted = kBundleNil;
        uint i = head;
        while (i != kBundleNil) {
            BundleNode n = nodes.nodes[i];
            uint rest = n.next & kBundleIndexMask;
            uint face = n.next & kBundleFrontFaceBit;
            if (sorted == kBundleNil || before(n.depth, i, nodes.nodes[sorted].depth, sorted)) {
                nodes.nodes[i].next = sorted | face;
                sorted = i;
            } else {
                uint at = sorted;
                uint after = nodes.nodes[at].next & kBundleIndexMask;
                while (after != kBundleNil && before(nodes.nodes[after].depth, after, n.depth, i)) {
                    at = after;
                    after = nodes.nodes[at].next & kBundleIndexMask;
                }
                nodes.nodes[i].next = after | face;
                nodes.nodes[at].next = i | (nodes.nodes[at].next & kBundleFrontFaceBit);
            }
            i = rest;
        }
        heads.heads[pixel] = sorted;
    }
    if (push.pool.previous != uvec2(0u)) {
        BundlePrevious previous = BundlePrevious(push.pool.previous);
        uint last = kBundleNil;
        for (uint i = heads.heads[pixel]; i != kBundleNil; i = nodes.nodes[i].next & kBundleIndexMask) {
            previous.previous[i] = last;
            last = i;
        }
    }
}
