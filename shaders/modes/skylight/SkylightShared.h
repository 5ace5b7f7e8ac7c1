// Host/device definitions of the skylight mode's visibility pass.
#ifndef BL_SKYLIGHT_SHARED_H
#define BL_SKYLIGHT_SHARED_H
#include "../../shared/Prelude.h"

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

// Own-surface tolerance across the pixel a point falls in: the point's surface, sampled at the
// pixel centre up to half a pixel diagonal (0.71 px) away, differs in depth by up to that times
// tan(incidence); 1 px * tan covers it with margin. Capped: beyond ~85 degrees the cosine weight
// makes the term negligible anyway.
BL_CONST float kSkylightOwnSurfacePixels = 1.0f;
BL_CONST float kSkylightMaxTangent = 12.0f;

BL_NAMESPACE_END
#endif
