#version 460
#extension GL_GOOGLE_include_directive : require
// Stores the distance from the light to the nearest surface, in world units (a float whose relative
// precision is the same at every scene scale), and that surface's shading normal (ShadowTexel.glsl).
#include "gpu/ShadowTexel.glsl"
#include "shared/GpuTypes.h"

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inNormal;
layout(push_constant) uniform PushBlock { ShadowPush push; };
layout(constant_id = kShadowSpecNormals) const bool kNormals = true;
layout(location = 0) out uvec4 outTexel;

void main() { outTexel = blPackShadowTexel(length(inWorld - push.lightPosition), kNormals ? inNormal : vec3(0.0)); }
