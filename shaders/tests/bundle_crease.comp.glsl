#version 460
#extension GL_GOOGLE_include_directive : require
// Runs the bundle walk of the path-tracing modes on points a test places: per query (point, normal
// n of either sign: the walk travels along the one of +-omega on n's side, as a path's next segment)
// 1 where it finds a surface ahead, 0 where it escapes, 2 where the point falls outside the frame;
// after the count results, the found surface's distance along the ray (float bits).
// centreOnly: x's own pixel alone (blBundleSurfaceNearest), else with the contact taps
// (blBundleSurfaceNearestAcrossCreases, what multibounce and bidir run).
#include "bundle/Traversal.glsl"

layout(local_size_x = 64) in;

#include "tests/BoxQueries.glsl"

layout(push_constant) uniform PushBlock {
    BundlePoolView pool;
    uvec2 queries;
    uvec2 results;
    uint count;
    uint centreOnly;
} push;

void main() {
    uint item = gl_GlobalInvocationID.x;
    if (item >= push.count) {
        return;
    }
    BoxQuery q = BoxQueries(push.queries).queries[item];
    vec3 x = q.position.xyz;
    vec3 n = q.normal.xyz;
    BundleFrame frame = blBundlePoolFrame(push.pool, 0u);
    BundleHeads heads = blBundlePoolHeads(push.pool, 0u);
    BundleNodes nodes = BundleNodes(push.pool.nodes);
    BundleHitPayload hits = BundleHitPayload(push.pool.payload);
    float dir = dot(n, frame.direction) >= 0.0 ? 1.0 : -1.0;
    ivec2 pixel;
    float depth;
    uint result = 2u;
    float distance = 0.0;
    if (blBundlePixel(frame, x, pixel, depth)) {
        float crossing;
        ivec2 hitPixel;
        uint hit = push.centreOnly != 0u
                       ? blBundleSurfaceNearest(nodes, blBundleHead(heads, frame, pixel), hits, true, kBundleNil, frame,
                                                pixel, x, depth, n, dir, crossing)
                       : blBundleSurfaceNearestAcrossCreases(nodes, heads, hits, kBundleNil, frame, pixel, x, depth, n,
                                                             dir, crossing, hitPixel);
        result = hit != kBundleNil ? 1u : 0u;
        distance = dir * (crossing - depth);
    }
    BoxAnswers(push.results).answers[item] = result;
    BoxAnswers(push.results).answers[push.count + item] = floatBitsToUint(distance);
}
