// Octahedral unit-vector encoding in 2 x 16-bit snorm (Cigolle et al. 2014), shared C++/GLSL.
#ifndef BL_SHARED_OCTAHEDRAL_H
#define BL_SHARED_OCTAHEDRAL_H
#include "Prelude.h"

BL_NAMESPACE_BEGIN

BL_INLINE vec2 blSignNotZero(vec2 v) { return vec2(v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f); }

BL_INLINE uint blPackOctahedral(vec3 n) {
    vec2 p = vec2(n.x, n.y) * (1.0f / (abs(n.x) + abs(n.y) + abs(n.z)));
    if (n.z <= 0.0f) {
        p = (vec2(1.0f) - abs(vec2(p.y, p.x))) * blSignNotZero(p);
    }
    return packSnorm2x16(p);
}

BL_INLINE vec3 blUnpackOctahedral(uint packed) {
    vec2 p = unpackSnorm2x16(packed);
    vec3 n = vec3(p.x, p.y, 1.0f - abs(p.x) - abs(p.y));
    if (n.z < 0.0f) {
        vec2 xy = (vec2(1.0f) - abs(vec2(n.y, n.x))) * blSignNotZero(vec2(n.x, n.y));
        n.x = xy.x;
        n.y = xy.y;
    }
    return normalize(n);
}

BL_NAMESPACE_END
#endif
