// Points sampled on the scene's emissive triangles for next-event estimation on the GPU (the
// "first shot" of issue 21): each iteration draws M points y_k by power and shadows them with
// cube maps, like virtual point lights. Shared by the host sampler (core/gpu/EmitterPointSampler.h) and
// the shaders (shaders/gpu/EmitterPointLight.glsl).
//
// Density of a point (area measure): the triangle is chosen with probability P_i = Phi_i / Phi,
// Phi_i = mean(L_e,i) A_i, then a point uniform on it, so p_A(y) = P_i / A_i = mean(L_e(y)) / Phi,
// the same for every point of equal radiance: the density the bundle strategy's MIS weight needs
// at an emitter it hits, from that emitter's radiance alone (blEmitterAreaPdf).
// The M-sample estimate of light reflected at x toward wo:
//   L(x, wo) ~ 1/M sum_k f(x, wi_k, wo) L_e(y_k) cos_x cos_y V(x, y_k) / (|x - y_k|^2 p_A(y_k)).
#ifndef BL_SHARED_EMITTER_POINTS_H
#define BL_SHARED_EMITTER_POINTS_H
#include "GpuTypes.h"

BL_NAMESPACE_BEGIN

// The buffer EmitterPointPass uploads: this header, then `count` GpuEmitterPoint.
struct GpuEmitterPointHeader {
    uint count;         // points this iteration (0: none; the modes' estimates then leave them out)
    uint resolution;    // texels per side of their shadow cubes' faces
    float inversePower; // 1 / Phi (blEmitterAreaPdf)
    uint pad;
};
BL_STATIC_ASSERT(sizeof(GpuEmitterPointHeader) == 16, "GpuEmitterPointHeader layout");

struct GpuEmitterPoint {
    vec3 position;   // y, on the emitter
    float areaPdf;   // p_A(y), per unit area
    vec3 normal;     // the emitter's front (geometric) normal at y, unit
    float pad0;
    vec3 emission;   // L_e(y), radiance from the front face
    float pad1;
    vec3 cubeCentre; // where its shadow cube is rendered: y lifted off the emitter along its normal
    float pad2;
};
BL_STATIC_ASSERT(sizeof(GpuEmitterPoint) == 64, "GpuEmitterPoint layout");

// mean(L_e): the channels' mean, each divided first so that no sum overflows a float.
BL_INLINE float blEmitterMeanRadiance(vec3 emission) {
    return emission.x * (1.0f / 3.0f) + emission.y * (1.0f / 3.0f) + emission.z * (1.0f / 3.0f);
}

// p_A of a point of radiance `emission`, given 1 / Phi (0 when the scene has no emitters).
BL_INLINE float blEmitterAreaPdf(vec3 emission, float inversePower) {
    return blEmitterMeanRadiance(emission) * inversePower;
}

BL_NAMESPACE_END
#endif
