#version 460
#extension GL_GOOGLE_include_directive : require
// The benchmark floor, one atomic per subgroup.
#define BL_SUBGROUP_ALLOCATION 1
#include "bundle/CountFragment.glsl"
