#version 460
#extension GL_GOOGLE_include_directive : require
// Runs the bundle traversal helpers on a pool slot so tests can check them against Embree:
//   walk: per pixel, its fragments in depth order by repeated next-steps (unsorted lists:
//         blBundleNext from the shallowest; sorted: blBundleSortedNext from the head), and the same
//         list backwards from the deepest (blBundlePrevious / blBundleSortedPrevious);
//   query: per query (pixel, depth, direction), blBundleNearest, and on sorted lists
//          blBundleSortedNearest.
#include "bundle/Traversal.glsl"

layout(local_size_x = 64) in;

struct TraversalQuery {
    uint pixel;
    float depth;
    float dir;
    float ownEpsilon;
};
layout(buffer_reference, std430, buffer_reference_align = 16) buffer Queries { TraversalQuery queries[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Results { uint results[]; };

layout(push_constant) uniform PushBlock {
    BundlePoolView pool;
    uvec2 queries;
    uvec2 results;
    uint slot;
    uint count;    // queries, or pixels for the walk
    uint maxWalk;  // walk: nodes written per pixel and direction
    uint walk;     // 1: walk, 0: query
} push;

void main() {
    uint item = gl_GlobalInvocationID.x;
    if (item >= push.count) {
        return;
    }
    BundleFrame frame = blBundlePoolFrame(push.pool, push.slot);
    BundleHeads heads = blBundlePoolHeads(push.pool, push.slot);
    BundleNodes nodes = BundleNodes(push.pool.nodes);
    Results out_ = Results(push.results);
    bool sorted = push.pool.sorted != 0u;
    if (push.walk == 1u) {
        uint head = heads.heads[item] & kBundleIndexMask;
        uint base = item * 2u * push.maxWalk;
        for (uint k = 0u; k < 2u * push.maxWalk; ++k) {
            out_.results[base + k] = kBundleNil;
        }
        if (head == kBundleNil) {
            return;
        }
        // The shallowest and deepest fragments: from the ends of a sorted list, else by search.
        uint first = head;
        if (!sorted) {
            for (uint i = head; i != kBundleNil; i = nodes.nodes[i].next & kBundleIndexMask) {
                if (blBundlePrevious(nodes, head, i) == kBundleNil) first = i;
            }
        }
        uint last = first;
        uint k = 0u;
        for (uint i = first; i != kBundleNil && k < push.maxWalk; ++k) {
            out_.results[base + k] = i;
            last = i;
            i = sorted ? blBundleSortedNext(nodes, i) : blBundleNext(nodes, head, i);
        }
        k = 0u;
        for (uint i = last; i != kBundleNil && k < push.maxWalk; ++k) {
            out_.results[base + push.maxWalk + k] = i;
            i = sorted ? blBundleSortedPrevious(BundlePrevious(push.pool.previous), i) : blBundlePrevious(nodes, head, i);
        }
        return;
    }
    TraversalQuery q = Queries(push.queries).queries[item];
    uint head = heads.heads[q.pixel] & kBundleIndexMask;
    out_.results[2u * item] = blBundleNearest(nodes, head, q.depth, q.dir, q.ownEpsilon, frame);
    out_.results[2u * item + 1u] = sorted ? blBundleSortedNearest(nodes, head, q.depth, q.dir, q.ownEpsilon, frame)
                                          : kBundleNil;
}
