#version 460
#extension GL_GOOGLE_include_directive : require
// Pool build fragment shader, variant: BL_COUNT_ONLY (see PoolAppend.glsl).
#define BL_COUNT_ONLY 1
#include "bundle/PoolAppend.glsl"
