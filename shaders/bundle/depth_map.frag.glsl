#version 460
#extension GL_GOOGLE_include_directive : require
// Orthographic depth map along the bundle direction (a directional shadow map): the fragment's
// linear depth, kept by the depth test as the largest, i.e. the surface nearest to a light at
// +infinity along omega. The bundle's vertex shader provides the depth varying.
layout(location = 0) in float inDepth;
layout(location = 1) in vec3 inNormal;
layout(location = 0) out float outDepth;

void main() { outDepth = inDepth; }
