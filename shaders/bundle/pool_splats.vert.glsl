#version 460
#extension GL_GOOGLE_include_directive : require
// Bundle build of point splats into a pool ([TO12p]): each splat is drawn as the equilateral
// triangle in its tangent plane that circumscribes its disc (3 vertices per splat, no vertex
// buffer); the fragment shader cuts it to the circle. The tangent-plane position of the corner
// travels as a varying (exact under an orthographic projection) for that cut.
#include "bundle/BundleBuffers.glsl"
#include "bundle/Projection.glsl"

layout(push_constant) uniform PushBlock { BundleDrawPush push; };

layout(location = 0) out float outDepth;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outDisc; // position in the disc's plane, in units of its radius
layout(location = 3) flat out uint outSplat;

// Corners of the equilateral triangle circumscribing the unit circle: circumradius 2.
const vec2 kCorners[3] = vec2[3](vec2(0.0, 2.0), vec2(-1.7320508, -1.0), vec2(1.7320508, -1.0));

void main() {
    BundleFrame frame = BundleFrames(push.frameAddress).frames[0];
    uint splatIndex = push.firstPrimitive + uint(gl_VertexIndex) / 3u;
    BundleSplat s = BundleSplats(push.splatAddress).splats[splatIndex];
    vec3 n = s.normal;
    // Tangent frame (Duff et al. 2017): continuous except at n.z = -1 exactly.
    float sign = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sign + n.z);
    float b = n.x * n.y * a;
    vec3 t = vec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    vec3 bt = vec3(b, sign + n.y * n.y * a, -n.y);
    vec2 corner = kCorners[uint(gl_VertexIndex) % 3u];
    vec3 world = s.position + s.radius * (corner.x * t + corner.y * bt);
    float depth;
    vec4 clip = blBundleClipPosition(frame, world, depth);
    outDepth = depth;
    outNormal = n;
    outDisc = corner;
    outSplat = splatIndex;
    gl_Position = clip;
    // A splat without a usable disc (radius not > 0, NaN, a normal far from unit) draws nothing:
    // every corner lands outside the clip volume.
    bool valid = s.radius > 0.0 && s.radius < 3.0e38 && abs(dot(n, n) - 1.0) < kBundleSplatNormalTolerance &&
                 all(equal(world, world));
    if (!valid) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    }
}
