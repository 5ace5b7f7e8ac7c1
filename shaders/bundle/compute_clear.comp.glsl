#version 460
#extension GL_GOOGLE_include_directive : require
// Compute bundle build, first pass: the slot's frame is written (so consumers of the pool read it
// as after a rasterized build) and its heads set to empty lists.
#include "bundle/BundleBuffers.glsl"
#include "bundle/ComputeBuildShared.h"

layout(local_size_x = kBundleComputeGroupSize) in;
layout(push_constant) uniform PushBlock { BundleComputeClearPush push; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i == 0u) {
        BundleFrames(push.frameAddress).frames[0] = push.frame;
    }
    if (i < push.pixels) {
        BundleHeads(push.headAddress).heads[i] = kBundleNil;
    }
}
