// Host/device definitions of the skylight mode's visibility pass.
#ifndef BL_SKYLIGHT_SHARED_H
#define BL_SKYLIGHT_SHARED_H
#include "../../shared/Accumulation.h"

BL_NAMESPACE_BEGIN

struct SkylightPush {
    uvec2 headAddress;
    uvec2 nodeAddress;
    vec3 radianceForward;  // L_e(omega): environment radiance arriving from omega
    float pdfForward;      // p_r(omega)
    vec3 radianceBackward; // L_e(-omega)
    float pdfBackward;     // p_r(-omega)
    uint width;            // camera image
    uint height;
    uint addBase;          // 1 for the tile that also handles escaping camera rays
    float environmentRotation;
    vec2 samplePosition;   // this iteration's sub-pixel camera sample, for background rays
    uint environmentPresent;
    uint visibility;       // kSkylightVisibilityBundle or kSkylightVisibilityDepthMap
};
BL_STATIC_ASSERT(sizeof(SkylightPush) == 80, "SkylightPush layout");

// Bundle: omega and -omega for every point (pdf p_r). Depth map (a directional shadow map): omega
// only, for the points on its side (pdf q on the sphere); the others wait for another direction.
BL_CONST uint kSkylightVisibilityBundle = 0u;
BL_CONST uint kSkylightVisibilityDepthMap = 1u;

BL_CONST uint kSkylightGroupSize = 8u;

// Layers the skylight mode writes: visible emitters and the environment behind the scene
// (1 segment), direct light from the environment (2 segments).
BL_CONST uint kSkylightAccumLayers = (1u << kPathEmitted) | (1u << kPathDirect);


BL_NAMESPACE_END
#endif
