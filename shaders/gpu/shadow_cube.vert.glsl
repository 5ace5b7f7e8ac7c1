#version 460
#extension GL_GOOGLE_include_directive : require
// Omnidirectional shadow map, one cube face per draw. Projection straight from the face basis of
// CubeFaces.h (no matrices, no API cube conventions): clip = (p.R, -p.U, near, p.F), i.e. reversed
// depth near/z, so the nearest surface has the largest depth.
#include "shared/CubeFaces.h"
#include "shared/GpuTypes.h"

layout(location = 0) in vec4 inPositionU;
layout(push_constant) uniform PushBlock { ShadowPush push; };
layout(location = 0) out vec3 outWorld;

void main() {
    vec3 world = (push.model * vec4(inPositionU.xyz, 1.0)).xyz;
    outWorld = world;
    vec3 p = world - push.lightPosition;
    vec3 r, u, f;
    blCubeFaceBasis(push.face, r, u, f);
    gl_Position = vec4(dot(p, r), -dot(p, u), push.nearPlane, dot(p, f));
}
