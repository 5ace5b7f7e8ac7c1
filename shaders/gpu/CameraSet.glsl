// The camera set (set 0) of a per-pixel shading pass: the G-buffer of this iteration, its camera,
// materials, the environment and the layered accumulator (core/gpu/CameraPass.h binds it). Define
// BL_ACCUM_LAYERS (the mode's layer mask) before including.
#ifndef BL_GPU_CAMERA_SET_GLSL
#define BL_GPU_CAMERA_SET_GLSL
#include "shared/Bindings.h"
#include "shared/Camera.h"
#include "shared/EnvMap.h"
#include "shared/GpuTypes.h"

layout(set = kCameraSet, binding = kCameraBindingGBuffer, rgba32f) uniform readonly image2D gbuffer[kGBufferAttachmentCount];
layout(set = kCameraSet, binding = kCameraBindingCamera) uniform CameraBlock { GpuCamera camera; };
layout(set = kCameraSet, binding = kCameraBindingMaterials) readonly buffer MaterialBlock { GpuMaterial materials[]; };
layout(set = kCameraSet, binding = kCameraBindingEnvironment) uniform sampler2D environment;

#define BL_ACCUM_SET kCameraSet
#define BL_ACCUM_BINDING kCameraBindingAccum
#include "gpu/Accumulate.glsl"

// Whether the camera sample of `pixel` hit a surface (else its ray escaped).
bool blCameraHitSurface(ivec2 pixel) { return imageLoad(gbuffer[kGBufferPosition], pixel).w > 0.0; }

// The triangle (global index, GpuScene order) the camera sample of `pixel` hit, and the sample's
// barycentrics (b1, b2) in it. Only meaningful where blCameraHitSurface(pixel).
uint blGBufferSurface(ivec2 pixel, out vec2 barycentrics) {
    vec4 s = imageLoad(gbuffer[kGBufferSurface], pixel);
    barycentrics = s.zw;
    return uint(s.x) | (uint(s.y) << 16);
}

// Radiance of an escaped camera ray through `pixel` at sub-pixel `samplePosition`: the
// environment when the scene has one (rotated by `rotation` radians about +y), else black.
vec3 blCameraBackground(ivec2 pixel, vec2 samplePosition, bool environmentPresent, float rotation) {
    if (!environmentPresent) {
        return vec3(0.0);
    }
    vec3 dir = blCameraRayDirection(camera, vec2(pixel) + samplePosition);
    return textureLod(environment, blEnvDirectionToUv(dir, rotation), 0.0).rgb;
}

#endif
