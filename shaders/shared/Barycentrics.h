// Barycentric coordinates of a point in a triangle, shared C++/GLSL: the bundle build's hit payload
// and the G-buffer's surface channel both locate their sample this way.
#ifndef BL_SHARED_BARYCENTRICS_H
#define BL_SHARED_BARYCENTRICS_H
#include "Prelude.h"

BL_NAMESPACE_BEGIN

// (b1, b2) of the point p0 + q in the triangle (p0, p0 + e1, p0 + e2), projected into its plane
// (q off the plane projects onto it); clamped into the triangle, since a rasterized sample can lie
// a rounding error outside the triangle it was given to. A degenerate triangle: its centre.
// By the cross products, b1 = ((q x e2) . n) / (n . n), b2 = ((e1 x q) . n) / (n . n) with
// n = e1 x e2, not by the Gram matrix's determinant (e1.e1)(e2.e2) - (e1.e2)^2: that subtracts two
// nearly equal numbers and is pure rounding once a triangle's aspect passes ~1e3-1e4 in float (a
// 559 x 0.056 sliver: 9.8e10 - 9.8e10 for 945), which put every hit of a sliver floor on a random
// point (or the centroid) of its triangle and multiplied the atlas's indirect light (issue 19).
// The cross products keep a relative error of ~eps * aspect. Edges are scaled to unit length
// first, so that n . n neither overflows nor underflows for large or small triangles.
BL_INLINE vec2 blTriangleBarycentrics(vec3 q, vec3 e1, vec3 e2) {
    float longest = max(max(abs(e1.x), abs(e1.y)), max(max(abs(e1.z), abs(e2.x)), max(abs(e2.y), abs(e2.z))));
    vec2 b = vec2(1.0f / 3.0f);
    if (longest > 0.0f) {
        float s = 1.0f / longest;
        vec3 a1 = e1 * s, a2 = e2 * s, r = q * s;
        vec3 n = cross(a1, a2);
        float nn = dot(n, n);
        if (nn > 0.0f) {
            b = vec2(dot(cross(r, a2), n), dot(cross(a1, r), n)) / nn;
        }
    }
    b = clamp(b, vec2(0.0f), vec2(1.0f));
    if (b.x + b.y > 1.0f) {
        b = b / (b.x + b.y);
    }
    return b;
}

BL_NAMESPACE_END
#endif
