#version 460
#extension GL_GOOGLE_include_directive : require
// Runs the depth maps' visibility test (bundle/DepthMapVisibility.glsl) on points a test places:
// per query (point, normal of either sign) 1 where the map hides it from the light along omega,
// 0 where it sees the light, 2 where it falls outside the map's frame. centreOnly: the pixel centre's
// test alone (what the test's mutation check runs).
#include "shared/BundleTypes.h"

layout(local_size_x = 64) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D depthMap;
layout(set = 0, binding = 1) uniform FrameBlock { BundleFrame frame; };
#define BL_DEPTH_MAP_TEXEL(pixel, layer) imageLoad(depthMap, pixel)
#include "bundle/DepthMapVisibility.glsl"

#include "tests/BoxQueries.glsl"

layout(push_constant) uniform PushBlock {
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
    ivec2 pixel;
    float depth;
    uint result = 2u;
    if (blBundlePixel(frame, x, pixel, depth)) {
        float cosine = dot(n, frame.direction);
        bool hidden = push.centreOnly != 0u ? blDepthMapCentreOccluded(frame, 0, pixel, x, depth, n, cosine)
                                            : blDepthMapOccluded(frame, 0, pixel, x, depth, n, cosine);
        result = hidden ? 1u : 0u;
    }
    BoxAnswers(push.results).answers[item] = result;
}
