// Host/device definitions of mode bidir (modes/bidir/BidirMode.h): the evaluation pass's set 1,
// its push constants and the VPL record. Set 0 is the camera set (core/gpu/CameraPass.h).
#ifndef BL_BIDIR_SHARED_H
#define BL_BIDIR_SHARED_H
#include "../../shared/Accumulation.h"
#include "../../shared/BundleTypes.h"
#include "../../shared/GpuTypes.h"
#include "../../shared/Lights.h"

BL_NAMESPACE_BEGIN

// Evaluation pass, set 1.
BL_CONST uint kBidirSet = 1u;
BL_CONST uint kBidirBindingLights = 0u;     // storage GpuLight[] (at the frame's time)
BL_CONST uint kBidirBindingShadowMaps = 1u; // storage image 2D array (rgba16ui): cube l = light l
BL_CONST uint kBidirBindingVplMaps = 2u;    // storage image 2D array (rgba16ui): cube k = VPL k
BL_CONST uint kBidirBindingVpls = 3u;       // storage BidirVpl[pairs]
BL_CONST uint kBidirBindingEmitterPoints = 4u;    // storage GpuEmitterPoint header + points (EmitterPoints.h)
BL_CONST uint kBidirBindingEmitterShadowMaps = 5u; // storage image 2D array (rgba16ui): cube k = emitter point k
BL_CONST uint kBidirBindingFrame = 8u;      // rgba32f 2D array: the frame's layers for interleaving (Interleave.h)
BL_CONST uint kBidirBindingInterleave = 12u; // storage InterleaveEvaluate (Interleave.h; the push block is full)

// Strategies of the one-bounce estimator ([TO12] Eq. 3-6).
BL_CONST uint kBidirStrategyVpl = 0u;    // j = 1: the middle vertex is a VPL from the light
BL_CONST uint kBidirStrategyBundle = 1u; // j = 2: the middle vertex is a bundle hit from x
BL_CONST uint kBidirStrategyMis = 2u;    // both, balance heuristic

// One VPL: the first surface y hit by a ray from light `light` along omega_{0,1} (sampled on the
// host, modes/bidir/VplSampler.h). Everything the shader needs to evaluate the path
// x0 -> y -> x for any camera point x.
struct BidirVpl {
    vec3 position;     // y
    uint light;        // index of the light it came from; the light count for the area emitters' source
    vec3 normal;       // shading normal at y turned toward the light (the lit side)
    uint material;     // material index at y
    vec3 albedo;       // albedo at y (material, texture applied on the host)
    float pdfLight;    // P(light) p_e(omega_{0,1}): solid-angle density of the light ray
    vec3 intensity;    // I(omega_{0,1}): the light's intensity along the ray, profile applied (area
                       // source: L_e cos0 / p_A(x0), VplSampler.h)
    float areaPdf;     // P(light) p_e(omega_{0,1}) (n_y . omega_{y,0}) / |y - x0|^2 (area measure)
    vec3 toLight;      // omega_{y,0}, unit
    uint valid;        // 0: the light ray escaped or hit a black / back-lit surface: adds nothing
    vec3 cubeCentre;   // where its shadow cube is rendered: y lifted off its surface
    uint pad0;
};
BL_STATIC_ASSERT(sizeof(BidirVpl) == 96, "BidirVpl layout");

struct BidirPush {
    BundlePoolView pool;       // the K bundles of this frame (hit payload)
    uint width;                // camera image
    uint height;
    uint pairs;                // K: VPL/bundle pairs this frame
    uint lightCount;
    uint shadowResolution;     // texels per light cube-face side
    uint vplResolution;        // texels per VPL cube-face side
    uint strategy;             // kBidirStrategy*
    float hemispherePdf;       // p_r(d) of a bundle direction on a point's hemisphere: 1 / (2 pi)
    float suppressionNeighbours; // m' of [TO12] section 5 (Suppression.h)
    uint environmentPresent;
    float environmentRotation; // radians about +y
    uint bounces;              // 1: one-bounce only; 2: also the two-bounce term ([TO12] Eq. 7-8)
    vec2 samplePosition;       // sub-pixel position of this frame's camera sample, in [0, 1)^2
    float twoBounceMinDistance2; // clamping of the two-bounce term only: |x1 - x2|^2 >= this (0: off)
    uint suppression;          // kBidirSuppression* (Suppression.h)
};
BL_STATIC_ASSERT(sizeof(BidirPush) == 128, "BidirPush layout");

BL_CONST uint kBidirGroupSize = 8u;

// p_e(omega): solid-angle density with which a traced VPL ray leaves light `l` along unit omega,
// the light chosen. Point lights: uniform on the sphere, 1 / (4 pi) ([TO12] section 4.1). Spot
// lights: proportional to the intensity, I(omega) / integral(I) ([TO12] 4.1): the profile
// (shared/Lights.h: 1 inside the inner cone, a smoothstep in cos between the cones) over its
// integral 2 pi ((1 - cosInner) + (cosInner - cosOuter) / 2), the smoothstep's mean being 1/2;
// zero outside the outer cone, where the profile is zero too. VplSampler.cpp samples it.
BL_INLINE float blBidirSpotProfileIntegral(GpuLight l) { return kPi * (2.0f - l.cosInner - l.cosOuter); }

BL_INLINE float blBidirEmissionPdf(GpuLight l, vec3 omega) {
    if (l.type != kLightSpot) {
        return 0.25f * kInvPi;
    }
    return blLightProfile(l, omega) / blBidirSpotProfileIntegral(l);
}

// Layers bidir writes: visible emitters (1 segment), direct light by shadow maps (2), one
// indirect bounce (3, the estimator of [TO12] Eq. 3-6) and two (4, Eq. 7-8; zero with bounces = 1).
BL_CONST uint kBidirAccumLayers =
    (1u << kPathEmitted) | (1u << kPathDirect) | (1u << kPathIndirect1) | (1u << kPathIndirect2);

BL_NAMESPACE_END
#endif
