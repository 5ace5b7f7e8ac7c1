// Pinhole camera rays, shared so that rasterized and ray-traced images line up pixel for pixel.
// Row 0 is the top of the image, column 0 the left (CONVENTIONS.md).
#ifndef BL_SHARED_CAMERA_H
#define BL_SHARED_CAMERA_H
#include "GpuTypes.h"

BL_NAMESPACE_BEGIN

// Unit direction of the ray through continuous pixel coordinates p (pixel centre = index + 0.5).
BL_INLINE vec3 blCameraRayDirection(GpuCamera cam, vec2 p) {
    float sx = (2.0f * p.x / cam.width - 1.0f) * cam.tanHalfX;
    float sy = (1.0f - 2.0f * p.y / cam.height) * cam.tanHalfY;
    return normalize(cam.forward + sx * cam.right + sy * cam.up);
}

BL_NAMESPACE_END
#endif
