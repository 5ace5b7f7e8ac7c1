#version 460
#extension GL_GOOGLE_include_directive : require
// Pool build fragment shader, variant: BL_EXACT_DEPTH (see PoolAppend.glsl).
#define BL_EXACT_DEPTH 1
#include "bundle/PoolAppend.glsl"
