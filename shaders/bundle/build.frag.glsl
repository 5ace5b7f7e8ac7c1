#version 460
#extension GL_GOOGLE_include_directive : require
// Bundle build, one atomic per fragment (any Vulkan 1.3 device).
#include "shared/GpuTypes.h"
#include "shared/Sampling.h"
#include "bundle/BuildFragment.glsl"
