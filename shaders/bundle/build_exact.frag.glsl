#version 460
#extension GL_GOOGLE_include_directive : require
// Bundle build with exact depths and faces (ray-plane intersection per fragment) and the surface
// payload: needs gl_PrimitiveID in fragments (the geometryShader feature). One atomic per fragment.
#define BL_EXACT_DEPTH 1
#include "shared/GpuTypes.h"
#include "shared/Sampling.h"
#include "bundle/BuildFragment.glsl"
