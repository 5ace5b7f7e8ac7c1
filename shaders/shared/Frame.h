// Orthonormal bases from a unit normal.
#ifndef BL_SHARED_FRAME_H
#define BL_SHARED_FRAME_H
#include "Prelude.h"

BL_NAMESPACE_BEGIN

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited": continuous except at n.z = -1's
// sign flip, no normalization needed.
BL_INLINE void blOrthonormalBasis(vec3 n, BL_OUT(vec3) t, BL_OUT(vec3) b) {
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

BL_NAMESPACE_END
#endif
