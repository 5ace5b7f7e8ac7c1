// Mode bidir: p_e(omega | light l), the density with which this frame's VPL rays leave light l,
// for directions the evaluation pass did not sample (MIS weights and suppression densities):
// reflective shadow maps' texel CDF (Rsm.h, vpl_source = rsm) or the traced rays' analytic
// density (BidirShared.h blBidirEmissionPdf, vpl_source = traced: the block's N is 0).
#include "modes/bidir/Rsm.h"

layout(set = kBidirSet, binding = kBidirBindingRsmCdf) readonly buffer RsmCdfBlock {
    uint rsmHeader[kBidirRsmHeaderWords];
    uint rsmStart[];
};

float blBidirLightPdf(uint l, GpuLight light, vec3 omega) {
    uint n = rsmHeader[0];
    if (n == 0u) {
        return blBidirEmissionPdf(light, omega);
    }
    float x, y;
    uint t = blRsmTexelOf(omega, n, x, y);
    uint perLight = 6u * n * n;
    uint base = l * perLight;
    uint next = t + 1u < perLight ? rsmStart[base + t + 1u] : 0u;
    return blRsmDirectionPdf(rsmStart[base + t], next, x, y, n);
}
