#version 460
#extension GL_GOOGLE_include_directive : require
// Stores the distance from the light to the nearest surface, in world units: a float whose
// relative precision is the same at every scene scale.
#include "shared/GpuTypes.h"

layout(location = 0) in vec3 inWorld;
layout(push_constant) uniform PushBlock { ShadowPush push; };
layout(location = 0) out float outDistance;

void main() { outDistance = length(inWorld - push.lightPosition); }
