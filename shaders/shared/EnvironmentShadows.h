// Directions drawn toward the environment for next-event estimation on the GPU (issue 21's first
// shot for environments), shared by the host pass (core/bundle/EnvironmentShadowPass.h) and the
// shaders (shaders/gpu/EnvironmentShadowLight.glsl). Each iteration draws K directions omega_k by
// the environment's importance q (DirectionSampler, Importance: luminance with a small uniform
// share) and renders an orthographic depth map along each (a directional shadow map: the surface
// nearest the light at +infinity along omega_k). The K-sample estimate of light reflected at x:
//   L(x, wo) ~ 1/K sum_k f(x, omega_k, wo) L_e(omega_k) max(0, n . omega_k) V(x, omega_k) / q(omega_k).
#ifndef BL_SHARED_ENVIRONMENT_SHADOWS_H
#define BL_SHARED_ENVIRONMENT_SHADOWS_H
#include "BundleTypes.h"

BL_NAMESPACE_BEGIN

// Multiple importance sampling against a strategy that reaches the environment by escaping along a
// direction of density p_d (multibounce's bundles): the balance heuristic's weights need the
// directions' density at any direction, on the GPU. They stay a partition of unity, and the
// estimate unbiased, with any positive stand-in for q evaluated the same way on both sides, so the
// shaders use q~(d) = luminanceScale lum(L_e(d)) + uniformDensity, the sampler's mixture (luminance
// + L_o, DirectionSampler) with the map's own bilinear radiance in place of its piecewise-constant
// table (shaders/gpu/EnvironmentShadowLight.glsl).
// The buffer EnvironmentShadowPass uploads: this header, then `count` GpuEnvironmentShadow.
struct GpuEnvironmentShadowHeader {
    uint count;           // directions this iteration with light (0: none; the estimates leave them out)
    uint requested;       // K: directions drawn per iteration (0: the pass is off), the MIS count
    float luminanceScale; // q~'s luminance factor: P / integral of lum(L_e) over the sphere
    float uniformDensity; // q~'s uniform part: (1 - P) / (4 pi); 1 / (4 pi) for a black environment
};
BL_STATIC_ASSERT(sizeof(GpuEnvironmentShadowHeader) == 16, "GpuEnvironmentShadowHeader layout");

struct GpuEnvironmentShadow {
    BundleFrame frame; // its depth map's frame; frame.direction = omega_k, toward the environment
    vec3 weight;       // L_e(omega_k) / (q(omega_k) K): the direction's factor in the estimate
    float pdf;         // q(omega_k), density on the sphere
};
BL_STATIC_ASSERT(sizeof(GpuEnvironmentShadow) == 112, "GpuEnvironmentShadow layout");

BL_NAMESPACE_END

#endif
