#version 460
#extension GL_GOOGLE_include_directive : require
// Bundle build with exact depths and faces, one atomic per subgroup.
#define BL_EXACT_DEPTH 1
#define BL_SUBGROUP_ALLOCATION 1
#include "shared/GpuTypes.h"
#include "shared/Sampling.h"
#include "bundle/BuildFragment.glsl"
