#version 460
#extension GL_GOOGLE_include_directive : require
// Orthographic depth map along the bundle direction (a directional shadow map): the fragment's
// linear depth, kept by the depth test as the largest, i.e. the surface nearest to a light at
// +infinity along omega, and that surface's shading normal (either sign: a flat face's plane, on
// smooth meshes close to it), which bundle/DepthMapVisibility.glsl needs to find creases. The
// bundle's vertex shader provides both varyings.
layout(location = 0) in float inDepth;
layout(location = 1) in vec3 inNormal;
layout(location = 0) out vec4 outDepthNormal;

void main() {
    float lengthSquared = dot(inNormal, inNormal);
    vec3 n = lengthSquared > 1e-30 ? inNormal * inversesqrt(lengthSquared) : vec3(0.0);
    outDepthNormal = vec4(inDepth, n);
}
