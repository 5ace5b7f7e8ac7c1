#version 460
#extension GL_GOOGLE_include_directive : require
// Pool build fragment shader, variant: BL_COUNT_ONLY BL_SUBGROUP_ALLOCATION (see PoolAppend.glsl).
#define BL_COUNT_ONLY 1
#define BL_SUBGROUP_ALLOCATION 1
#include "bundle/PoolAppend.glsl"
