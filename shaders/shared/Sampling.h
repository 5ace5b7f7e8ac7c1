// Warps from [0,1)^2 to directions and points, with their densities. Shared by the CPU reference
// and GPU modes so both sample exactly alike.
#ifndef BL_SHARED_SAMPLING_H
#define BL_SHARED_SAMPLING_H
#include "Frame.h"

BL_NAMESPACE_BEGIN

// Cosine-weighted direction about +z (Malley's method on a concentric disk); pdf = cos / pi.
BL_INLINE vec3 blSampleCosineHemisphere(vec2 u) {
    vec2 o = 2.0f * u - vec2(1.0f);
    vec2 d = vec2(0.0f);
    if (o.x != 0.0f || o.y != 0.0f) {
        float r;
        float theta;
        if (abs(o.x) > abs(o.y)) {
            r = o.x;
            theta = (0.25f * kPi) * (o.y / o.x);
        } else {
            r = o.y;
            theta = 0.5f * kPi - (0.25f * kPi) * (o.x / o.y);
        }
        d = r * vec2(cos(theta), sin(theta));
    }
    return vec3(d.x, d.y, sqrt(max(0.0f, 1.0f - d.x * d.x - d.y * d.y)));
}

// Uniform direction on the sphere; pdf = 1 / (4 pi).
BL_INLINE vec3 blSampleUniformSphere(vec2 u) {
    float z = 1.0f - 2.0f * u.x;
    float r = sqrt(max(0.0f, 1.0f - z * z));
    float phi = kTwoPi * u.y;
    return vec3(r * cos(phi), r * sin(phi), z);
}

// Uniform barycentrics (b1, b2) of a triangle (Heitz 2019's low-distortion map); b0 = 1 - b1 - b2.
BL_INLINE vec2 blSampleTriangle(vec2 u) {
    vec2 b;
    if (u.x < u.y) {
        b.x = 0.5f * u.x;
        b.y = u.y - b.x;
    } else {
        b.y = 0.5f * u.y;
        b.x = u.x - b.y;
    }
    return b;
}

// Local frame <-> world frame about the unit normal n.
BL_INLINE vec3 blToWorld(vec3 local, vec3 n) {
    vec3 t;
    vec3 b;
    blOrthonormalBasis(n, t, b);
    return local.x * t + local.y * b + local.z * n;
}

BL_INLINE float blPowerHeuristic(float a, float b) {
    float a2 = a * a;
    float b2 = b * b;
    return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

BL_INLINE float blLuminance(vec3 c) { return dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }

BL_NAMESPACE_END
#endif
