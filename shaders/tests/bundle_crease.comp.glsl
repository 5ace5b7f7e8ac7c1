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
    BoxQueryPush box;
} push;

void main() {
    vec3 x, n;
    if (!blBoxQuery(push.box, x, n)) {
        return;
    }
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
        uint hit = push.box.centreOnly != 0u
                       ? blBundleSurfaceNearest(nodes, blBundleHead(heads, frame, pixel), hits, kBundleNil, frame,
                                                pixel, x, depth, n, dir, crossing)
                       : blBundleSurfaceNearestAcrossCreases(nodes, heads, hits, kBundleNil, frame, pixel, x, depth, n,
                                                             dir, crossing, hitPixel);
        result = hit != kBundleNil ? 1u : 0u;
        distance = dir * (crossing - depth);
    }
    uint item = gl_GlobalInvocationID.x;
    BoxAnswers(push.box.results).answers[item] = result;
    BoxAnswers(push.box.results).answers[push.box.count + item] = floatBitsToUint(distance);
}
