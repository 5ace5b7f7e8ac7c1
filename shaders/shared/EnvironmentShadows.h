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

// The buffer EnvironmentShadowPass uploads: this header, then `count` GpuEnvironmentShadow.
struct GpuEnvironmentShadowHeader {
    uint count; // directions this iteration (0: none; the modes' estimates then leave them out)
    uint pad0;
    uint pad1;
    uint pad2;
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
