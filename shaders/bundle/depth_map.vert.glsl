#version 460
#extension GL_GOOGLE_include_directive : require
// Bundle build: parallel projection of one mesh along the bundle direction, no culling, no depth
// test. The linear depth (world units along omega) travels as a varying: exact under an
// orthographic projection.
#include "bundle/Projection.glsl"

layout(location = 0) in vec4 inPositionU;
layout(location = 1) in vec4 inNormalV;

layout(set = 0, binding = 0) uniform FrameBlock { BundleFrame frame; };
layout(push_constant) uniform PushBlock { BundleDepthMapPush push; };

layout(location = 0) out float outDepth;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec3 outRelative; // world - frame.origin: the facet's plane, by derivatives

void main() {
    vec3 world = (push.model * vec4(inPositionU.xyz, 1.0)).xyz;
    float depth;
    vec4 clip = blBundleClipPosition(frame, world, depth);
    outDepth = depth;
    outNormal = mat3(push.model) * inNormalV.xyz;
    outRelative = world - frame.origin;
    gl_Position = clip;
}
