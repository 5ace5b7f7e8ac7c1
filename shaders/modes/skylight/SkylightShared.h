// Host/device definitions of the skylight mode's visibility pass.
#ifndef BL_SKYLIGHT_SHARED_H
#define BL_SKYLIGHT_SHARED_H
#include "../../shared/Accumulation.h"
#include "../../shared/EnvMap.h"

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
    uvec2 irradianceAddress; // IrradianceTable entries (vec4), when controlVariate != 0
    uint controlVariate;   // 1: add lambert E(n) and subtract the unoccluded lambert sample
    uint glossyControl;    // 1: add a lobe-sampled unoccluded glossy sample, subtract the bundle's
    uint seed;             // the run's seed and this direction's index: the lobe samples' stream
    uint iteration;
    uvec2 counterAddress;  // bundle visibility: the pool's BundleCounters (an overflowed build adds nothing)
    uvec2 hitAddress;      // bundle visibility: the nodes' BundleHit payload (each fragment's facet plane)
};
BL_STATIC_ASSERT(sizeof(SkylightPush) == 120, "SkylightPush layout");

// Bundle: omega and -omega for every point (pdf p_r). Depth map (a directional shadow map): omega
// only, for the points on its side (pdf q on the sphere); the others wait for another direction.
BL_CONST uint kSkylightVisibilityBundle = 0u;
BL_CONST uint kSkylightVisibilityDepthMap = 1u;

BL_CONST uint kSkylightGroupSize = 8u;

// The irradiance table of the control variate (modes/skylight/IrradianceTable.h): E at normals on
// a lat-long grid, column i at u = i / width, row j at v = j / (height - 1) (both poles are rows).
BL_CONST uint kSkylightIrradianceWidth = 128u;
BL_CONST uint kSkylightIrradianceHeight = 65u;

// The four table entries around normal n (rows y0, y0 + 1; columns x0, x0 + 1 wrapping) and the
// bilinear weights between them.
BL_INLINE uvec4 blSkylightIrradianceTaps(vec3 n, BL_OUT(vec2) weights) {
    vec2 uv = blEnvDirectionToUv(n, 0.0f);
    float fx = uv.x * float(kSkylightIrradianceWidth);
    float fy = uv.y * float(kSkylightIrradianceHeight - 1u);
    uint x0 = min(uint(fx), kSkylightIrradianceWidth - 1u);
    uint y0 = min(uint(fy), kSkylightIrradianceHeight - 2u);
    weights = vec2(fx - float(x0), fy - float(y0));
    uint x1 = (x0 + 1u) % kSkylightIrradianceWidth;
    uint row = y0 * kSkylightIrradianceWidth;
    return uvec4(row + x0, row + x1, row + kSkylightIrradianceWidth + x0, row + kSkylightIrradianceWidth + x1);
}

// Layers the skylight mode writes: visible emitters and the environment behind the scene
// (1 segment), direct light from the environment (2 segments).
BL_CONST uint kSkylightAccumLayers = (1u << kPathEmitted) | (1u << kPathDirect);


BL_NAMESPACE_END
#endif
