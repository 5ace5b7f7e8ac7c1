// Host/device definitions of the raster mode's shading pass.
#ifndef BL_RASTER_SHARED_H
#define BL_RASTER_SHARED_H
#include "../../shared/Accumulation.h"

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

// Layers the raster mode writes: visible emitters and the environment (1 segment), direct light
// from point and spot lights and area emitters (2 segments).
BL_CONST uint kRasterAccumLayers = (1u << kPathEmitted) | (1u << kPathDirect);

BL_CONST uint kRasterGroupSize = 8u;

// Specialization constants of the shading pass: which kinds of light the scene's plan runs (1) or
// leaves out (0). A SIMD CPU driver (lavapipe) runs a loop's body at least once under a lane mask
// even with no light to loop over, so each kind left out is compiled out instead.
BL_CONST uint kRasterSpecPointLights = 0u;   // point and spot lights (their shadow cubes)
BL_CONST uint kRasterSpecEmitterPoints = 1u; // emitter points (area emitters)
BL_CONST uint kRasterSpecEnvironment = 2u;   // environment directions
BL_CONST uint kRasterSpecCount = 3u;

BL_NAMESPACE_END
#endif
