// Lat-long environment map orientation (CONVENTIONS.md): column u = x/W, row from the top v = y/H,
//   phi = 2 pi (u - 0.5), theta = pi v, d = (cos phi sin theta, cos theta, sin phi sin theta).
// `rotation` (radians) turns the map about +y: the world direction d sees the map's direction
// R_y(-rotation) d.
#ifndef BL_SHARED_ENVMAP_H
#define BL_SHARED_ENVMAP_H
#include "Prelude.h"

BL_NAMESPACE_BEGIN

BL_INLINE vec3 blEnvRotate(vec3 d, float angle) {
    float c = cos(angle);
    float s = sin(angle);
    // Rotation about +y by `angle`, right-handed.
    return vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}

BL_INLINE vec2 blEnvDirectionToUv(vec3 d, float rotation) {
    vec3 m = blEnvRotate(d, -rotation);
    float u = atan(m.z, m.x) * (0.5f * kInvPi) + 0.5f;
    float v = acos(clamp(m.y, -1.0f, 1.0f)) * kInvPi;
    return vec2(u - floor(u), v);
}

BL_INLINE vec3 blEnvUvToDirection(vec2 uv, float rotation) {
    float phi = kTwoPi * (uv.x - 0.5f);
    float theta = kPi * uv.y;
    vec3 m = vec3(cos(phi) * sin(theta), cos(theta), sin(phi) * sin(theta));
    return blEnvRotate(m, rotation);
}

BL_NAMESPACE_END
#endif
