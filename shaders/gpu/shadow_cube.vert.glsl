#version 460
#extension GL_GOOGLE_include_directive : require
// Omnidirectional shadow map, one cube face per draw. Projection straight from the face basis of
// CubeFaces.h (no matrices, no API cube conventions): clip = (p.R, -p.U, near, p.F), i.e. reversed
// depth near/z, so the nearest surface has the largest depth.
#include "shared/CubeFaces.h"
#include "shared/GpuTypes.h"

layout(location = 0) in vec4 inPositionU;
layout(location = 1) in vec4 inNormalV;
layout(push_constant) uniform PushBlock { ShadowPush push; };
layout(constant_id = kShadowSpecNormals) const bool kNormals = true;
layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;

void main() {
    vec3 world = (push.model * vec4(inPositionU.xyz, 1.0)).xyz;
    outWorld = world;
    outNormal = kNormals ? mat3(push.model) * inNormalV.xyz : vec3(0.0); // rigid transforms (as depth_map.vert.glsl)
    vec3 p = world - push.lightPosition;
    vec3 r, u, f;
    blCubeFaceBasis(push.face, r, u, f);
    gl_Position = vec4(dot(p, r), -dot(p, u), push.nearPlane, dot(p, f));
}
