// Cube-map faces for omnidirectional shadow maps. Rendering and lookup both use these bases, so
// the shadow maps never depend on any API's cube-map conventions. Face f looks along F with R to
// the right and U up; a point p (relative to the light) on face f projects to
//   x = p.R / p.F, y = p.U / p.F in [-1, 1],  texel column (x + 1)/2 N, row (1 - y)/2 N.
#ifndef BL_SHARED_CUBE_FACES_H
#define BL_SHARED_CUBE_FACES_H
#include "Prelude.h"

BL_NAMESPACE_BEGIN

BL_INLINE void blCubeFaceBasis(uint face, BL_OUT(vec3) r, BL_OUT(vec3) u, BL_OUT(vec3) f) {
    if (face == 0u) { f = vec3(1, 0, 0); u = vec3(0, 1, 0); }
    else if (face == 1u) { f = vec3(-1, 0, 0); u = vec3(0, 1, 0); }
    else if (face == 2u) { f = vec3(0, 1, 0); u = vec3(0, 0, -1); }
    else if (face == 3u) { f = vec3(0, -1, 0); u = vec3(0, 0, 1); }
    else if (face == 4u) { f = vec3(0, 0, 1); u = vec3(0, 1, 0); }
    else { f = vec3(0, 0, -1); u = vec3(0, 1, 0); }
    r = cross(f, u);
}

// The face whose frustum contains direction d (major axis).
BL_INLINE uint blCubeFaceOf(vec3 d) {
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) { return d.x >= 0.0f ? 0u : 1u; }
    if (a.y >= a.z) { return d.y >= 0.0f ? 2u : 3u; }
    return d.z >= 0.0f ? 4u : 5u;
}

BL_NAMESPACE_END
#endif
