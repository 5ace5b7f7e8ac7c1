// Reflective shadow maps of mode bidir ([TO12] section 4.1; modes/bidir/ReflectiveShadowMap.h):
// host/device definitions shared by the RSM sampling pass, the host that completes each VPL and
// the evaluation pass that needs the same emission density for MIS.
//
// One cube per point/spot light, faces and texels as the shadow cubes (shared/CubeFaces.h): a unit
// direction omega on face f projects to x = omega.R / omega.F, y = omega.U / omega.F in [-1, 1],
// texel column floor((x + 1) / 2 N), row floor((1 - y) / 2 N), texel t = f N^2 + row N + col.
// Each face is rendered by the G-buffer pass from the light with one uniform sub-texel jitter per
// face and frame, so the point a texel holds is the first hit along a direction uniform over the
// texel's square on the face plane (at distance 1). Texel t of light l is chosen with probability
// P(t) = (start[t + 1] - start[t]) / 2^32 (a 32-bit fixed-point CDF built on the host from the
// light's flux through the texel, I(omega) times its solid angle), so the direction density is
//   p_e(omega) = P(t(omega)) J(omega) / A,  J = (1 + x^2 + y^2)^{3/2} = dA / dOmega,  A = (2 / N)^2,
// exact for the directions the host's rounding of the CDF gives (no texel discretization: the
// jitter makes every direction of a texel reachable; only the rasterizer's sample precision stands
// between the RSM's point and the ray's first hit).
#ifndef BL_BIDIR_RSM_H
#define BL_BIDIR_RSM_H
#include "../../shared/CubeFaces.h"
#include "../../shared/GpuTypes.h"
#include "../../shared/Random.h"

BL_NAMESPACE_BEGIN

// The evaluation pass's set 1 (BidirShared.h): the CDF block of vpl_source = rsm (header N = 0:
// traced VPLs, p_e of blBidirEmissionPdf).
BL_CONST uint kBidirBindingRsmCdf = 9u;

// The RSM sampling pass (rsm_sample.comp.glsl): set 0.
BL_CONST uint kBidirRsmBindingPosition = 0u; // the face's G-buffer attachments (storage images)
BL_CONST uint kBidirRsmBindingNormal = 1u;
BL_CONST uint kBidirRsmBindingAlbedo = 2u;
BL_CONST uint kBidirRsmBindingCdf = 3u;     // BidirRsmCdf block: resolution, then start[] per light
BL_CONST uint kBidirRsmBindingTexels = 4u;  // BidirRsmTexel[pairs], read back by the host
BL_CONST uint kBidirRsmGroupSize = 64u;
BL_CONST uint kBidirRsmHeaderWords = 4u;    // the CDF block's header: resolution N (0: no RSM), pad

// What the sampling pass gathers for VPL k: the texel it chose and what the RSM holds there.
struct BidirRsmTexel {
    vec4 position; // xyz world position, w > 0: a surface (else the light ray escaped)
    vec4 normal;   // xyz shading normal facing the light, w = material index
    vec4 albedo;   // rgb albedo with its texture
    uint light;    // the light chosen
    uint texel;    // t = face N^2 + row N + col
    uint written;  // 1 once the face holding t was gathered
    uint pad0;
};
BL_STATIC_ASSERT(sizeof(BidirRsmTexel) == 64, "BidirRsmTexel layout");

struct BidirRsmPush {
    uint pairs;      // K
    uint light;      // this dispatch's light and face: VPLs whose texel lies elsewhere wait
    uint face;
    uint resolution; // N
    uint lightCount;
    uint key;        // hash key of this frame's pairs (seed, high bits of the pair index)
    uint first;      // low 32 bits of the first pair's index
    uint pad0;
};
BL_STATIC_ASSERT(sizeof(BidirRsmPush) == 32, "BidirRsmPush layout");

// Face, texel and face-plane coordinates (x, y) of unit direction omega.
BL_INLINE uint blRsmTexelOf(vec3 omega, uint n, BL_OUT(float) x, BL_OUT(float) y) {
    uint face = blCubeFaceOf(omega);
    vec3 r, u, f;
    blCubeFaceBasis(face, r, u, f);
    float fz = dot(omega, f);
    x = dot(omega, r) / fz;
    y = dot(omega, u) / fz;
    uint col = min(uint(max((x + 1.0f) * 0.5f * float(n), 0.0f)), n - 1u);
    uint row = min(uint(max((1.0f - y) * 0.5f * float(n), 0.0f)), n - 1u);
    return face * n * n + row * n + col;
}

// p_e(omega) given the texel's start and its successor's (wrapping to 2^32 for the last texel).
BL_INLINE float blRsmDirectionPdf(uint start, uint next, float x, float y, uint n) {
    float probability = float(next - start) * 2.3283064365386963e-10f; // 2^-32
    float j = 1.0f + x * x + y * y;
    return probability * j * sqrt(j) * float(n) * float(n) * 0.25f;
}

// The hash stream of VPL sampling: the light (call 0) and the texel (call 1) of pair `index`.
BL_INLINE uint blRsmRandom(uint key, uint index, uint call) {
    return blHash(key ^ blHash(2u * index + call + 0x7f4a7c15u));
}

BL_NAMESPACE_END
#endif
