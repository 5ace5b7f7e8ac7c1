#version 460
#extension GL_GOOGLE_include_directive : require
// Compiles the bundle traversal helpers (and exercises them on one list) so their GLSL stays valid.
#include "bundle/Traversal.glsl"

layout(local_size_x = 1) in;
layout(set = 0, binding = 0) uniform FrameBlock { BundleFrame frame; };
layout(push_constant) uniform PushBlock { uvec2 heads; uvec2 nodes; vec4 point; } push;
layout(set = 0, binding = 1) buffer Out { uint results[4]; };

void main() {
    ivec2 pixel;
    float depth;
    if (!blBundlePixel(frame, push.point.xyz, pixel, depth)) {
        return;
    }
    BundleNodes nodes = BundleNodes(push.nodes);
    uint head = blBundleHead(BundleHeads(push.heads), frame, pixel);
    results[0] = blBundleNearest(nodes, head, depth, 1.0, frame.depthEpsilon, frame);
    results[1] = blBundleNearest(nodes, head, depth, -1.0, frame.depthEpsilon, frame);
    results[2] = head == kBundleNil ? kBundleNil : blBundleNext(nodes, head, head);
    results[3] = head == kBundleNil ? kBundleNil : blBundlePrevious(nodes, head, head);
}
