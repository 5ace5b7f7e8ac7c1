#version 460
#extension GL_GOOGLE_include_directive : require
// The benchmark floor: the same rasterization as a bundle build, but each fragment only
// increments a counter.
#include "bundle/BundleBuffers.glsl"

layout(location = 0) in float inDepth;
layout(location = 1) in vec3 inNormal;
layout(push_constant) uniform PushBlock { BundleBuildPush push; };

void main() {
    if (!gl_HelperInvocation) {
        atomicAdd(BundleCounterBlock(push.counterAddress).counters.requested, 1u);
    }
}
