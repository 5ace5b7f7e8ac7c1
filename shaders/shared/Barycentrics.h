// Barycentric coordinates of a point in a triangle, shared C++/GLSL: the bundle build's hit payload
// and the G-buffer's surface channel both locate their sample this way.
#ifndef BL_SHARED_BARYCENTRICS_H
#define BL_SHARED_BARYCENTRICS_H
#include "Prelude.h"

BL_NAMESPACE_BEGIN

// (b1, b2) of the point p0 + q in the triangle (p0, p0 + e1, p0 + e2), by least squares in its
// plane (q off the plane projects onto it); clamped into the triangle, since a rasterized sample
// can lie a rounding error outside the triangle it was given to. A degenerate triangle: its centre.
BL_INLINE vec2 blTriangleBarycentrics(vec3 q, vec3 e1, vec3 e2) {
    float d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2);
    float d20 = dot(q, e1), d21 = dot(q, e2);
    float denominator = d00 * d11 - d01 * d01;
    vec2 b = denominator > 0.0f ? vec2(d11 * d20 - d01 * d21, d00 * d21 - d01 * d20) / denominator
                                : vec2(1.0f / 3.0f);
    b = clamp(b, vec2(0.0f), vec2(1.0f));
    if (b.x + b.y > 1.0f) {
        b = b / (b.x + b.y);
    }
    return b;
}

BL_NAMESPACE_END
#endif
