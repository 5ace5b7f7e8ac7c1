#version 460
#extension GL_GOOGLE_include_directive : require
// Pool build fragment shader, variant: BL_SPLATS BL_SUBGROUP_ALLOCATION (see PoolAppend.glsl).
#define BL_SPLATS 1
#define BL_SUBGROUP_ALLOCATION 1
#include "bundle/PoolAppend.glsl"
