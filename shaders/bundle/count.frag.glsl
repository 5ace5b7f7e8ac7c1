#version 460
#extension GL_GOOGLE_include_directive : require
// The benchmark floor, one atomic per fragment.
#include "bundle/CountFragment.glsl"
