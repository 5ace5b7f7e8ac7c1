#version 460
#extension GL_GOOGLE_include_directive : require
// Pool build fragment shader, variant: interpolated depths, one atomic per fragment (see PoolAppend.glsl).
#include "bundle/PoolAppend.glsl"
