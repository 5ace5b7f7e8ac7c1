// Host/device definitions of the raster mode's shading pass.
#ifndef BL_RASTER_SHARED_H
#define BL_RASTER_SHARED_H
#include "../../shared/Prelude.h"

BL_NAMESPACE_BEGIN

struct RasterPush {
    uint lightCount;
    uint shadowResolution; // texels per cube-face side
    uint environmentPresent;
    float environmentRotation; // radians about +y
    vec2 samplePosition;       // sub-pixel position of this iteration's sample, in [0, 1)^2
    uint width;
    uint height;
};
BL_STATIC_ASSERT(sizeof(RasterPush) == 32, "RasterPush layout");

// Relative tolerance of the shadow test (receiver-plane depth against the stored distance). The
// receiver's own distance is reproduced to float precision (~1e-6) for planar receivers; 1e-3
// also covers curved receivers over a 4x4-texel PCF footprint, and, being relative, holds at any
// scene scale.
BL_CONST float kShadowRelativeBias = 1e-3f;

BL_CONST uint kRasterGroupSize = 8u;

BL_NAMESPACE_END
#endif
