#version 460
#extension GL_GOOGLE_include_directive : require
// Bundle build, one atomic per subgroup (devices with subgroup ballot and shuffle in fragments).
#define BL_SUBGROUP_ALLOCATION 1
#include "shared/GpuTypes.h"
#include "shared/Sampling.h"
#include "bundle/BuildFragment.glsl"
