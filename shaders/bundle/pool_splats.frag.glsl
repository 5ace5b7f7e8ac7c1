#version 460
#extension GL_GOOGLE_include_directive : require
// Pool build fragment shader, variant: BL_SPLATS (see PoolAppend.glsl).
#define BL_SPLATS 1
#include "bundle/PoolAppend.glsl"
