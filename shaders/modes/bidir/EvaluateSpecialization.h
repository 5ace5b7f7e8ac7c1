// Specialization constants of mode bidir's evaluation pass (evaluate.comp.glsl): settings and
// scene facts fixed for the pipeline's life that decide whole code paths (strategy, bounces,
// suppression, glossy or textured materials, environment bundles, reflective shadow maps, PCF taps). The
// host (BidirMode::setScene) passes them in this order, constant_id = index. Why constants and
// not push constants: the compiler then drops the paths they rule out, and lavapipe, which
// executes both sides of every branch under a lane mask, would otherwise pay for all of them on
// every pixel and pair (the suppression and Ashikhmin-Shirley lobes of every BRDF call, the
// environment bundles' walk, the texture lookup, ...). The results are the same either way.
#ifndef BL_BIDIR_EVALUATE_SPECIALIZATION_H
#define BL_BIDIR_EVALUATE_SPECIALIZATION_H
#include "../../shared/Prelude.h"

BL_NAMESPACE_BEGIN

BL_CONST uint kBidirSpecStrategy = 0u;    // kBidirStrategy* (BidirShared.h)
BL_CONST uint kBidirSpecBounces = 1u;     // 1 or 2
BL_CONST uint kBidirSpecSuppression = 2u; // kBidirSuppression* (Suppression.h), none where it changes nothing
BL_CONST uint kBidirSpecGlossy = 3u;      // 1: some material has a specular lobe (0: every BRDF is Lambert)
BL_CONST uint kBidirSpecTextured = 4u;    // 1: some material has an albedo texture
BL_CONST uint kBidirSpecEnvironment = 5u; // 1: environment bundles light the scene
BL_CONST uint kBidirSpecRsm = 6u;         // 1: VPLs from reflective shadow maps (their texel CDF gives p_e)
BL_CONST uint kBidirSpecVplTaps = 7u;     // PCF taps a side of the VPL cubes' lookups (vpl_shadow_taps)
BL_CONST uint kBidirSpecAreaVpls = 8u;    // 1: the VPL sources include the area emitters (VplSampler.h; index lightCount)
BL_CONST uint kBidirSpecCount = 9u;

BL_NAMESPACE_END
#endif
