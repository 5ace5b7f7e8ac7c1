#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer: transforms one mesh by its rigid transform at the frame's time.
#include "shared/Bindings.h"
#include "shared/GpuTypes.h"

layout(location = 0) in vec4 inPositionU;
layout(location = 1) in vec4 inNormalV;

layout(set = 0, binding = kGBufferBindingCamera) uniform CameraBlock { GpuCamera camera; };
layout(push_constant) uniform PushBlock { GBufferPush push; };

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUv;

void main() {
    vec4 world = push.model * vec4(inPositionU.xyz, 1.0);
    outWorld = world.xyz;
    outNormal = mat3(push.model) * inNormalV.xyz;
    outUv = vec2(inPositionU.w, inNormalV.w);
    gl_Position = camera.viewProj * world;
    // Sub-pixel jitter, in NDC units, for the progressive box filter.
    gl_Position.xy += push.jitter * gl_Position.w;
}
