#version 460
#extension GL_GOOGLE_include_directive : require
// Orthographic depth map along the bundle direction (a directional shadow map): the fragment's
// linear depth, kept by the depth test as the largest, i.e. the surface nearest to a light at
// +infinity along omega, and the plane of that surface's facet (its geometric normal, either
// sign), which bundle/DepthMapVisibility.glsl judges x's ray against and finds creases with. The
// facet's normal comes from the derivatives of the position relative to the frame's origin (exact
// on a triangle, whose attributes the quad's helper lanes interpolate too; relative, so a scene
// far from the origin keeps its digits); the interpolated shading normal only where those vanish.
// A smooth mesh's shading normal is not its facet's plane: with it the bowl of
// RasterScenes.EnvironmentLightsCurvedAndRoughMeshesAsTheReferenceDoes read 0.62 of the reference.
layout(location = 0) in float inDepth;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec3 inRelative;
layout(location = 0) out vec4 outDepthNormal;

void main() {
    // The derivatives made unit first: a nanometre scene's are ~1e-10 a pixel, whose cross
    // product's square would underflow float (DepthMapPassTest).
    vec3 a = dFdx(inRelative), b = dFdy(inRelative);
    float aa = dot(a, a), bb = dot(b, b);
    vec3 g = aa > 0.0 && bb > 0.0 ? cross(a * inversesqrt(aa), b * inversesqrt(bb)) : vec3(0.0);
    float gg = dot(g, g);
    float lengthSquared = dot(inNormal, inNormal);
    vec3 n = gg > 1e-12 ? g * inversesqrt(gg) : lengthSquared > 1e-30 ? inNormal * inversesqrt(lengthSquared) : vec3(0.0);
    outDepthNormal = vec4(inDepth, n);
}
