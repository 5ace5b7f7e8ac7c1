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

layout(push_constant) uniform PushBlock { BoxQueryPush box; } push;

void main() {
    vec3 x, n;
    if (!blBoxQuery(push.box, x, n)) {
        return;
    }
    ivec2 pixel;
    float depth;
    uint result = 2u;
    if (blBundlePixel(frame, x, pixel, depth)) {
        float cosine = dot(n, frame.direction);
        bool hidden = push.box.centreOnly != 0u ? blDepthMapCentreOccluded(frame, 0, pixel, x, depth, n, cosine)
                                            : blDepthMapOccluded(frame, 0, pixel, x, depth, n, cosine);
        result = hidden ? 1u : 0u;
    }
    BoxAnswers(push.box.results).answers[gl_GlobalInvocationID.x] = result;
}
