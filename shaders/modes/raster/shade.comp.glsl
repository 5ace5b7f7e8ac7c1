#version 460
#extension GL_GOOGLE_include_directive : require
// Raster mode shading: emitted radiance of visible emitters, direct light from point and spot
// lights (cube shadow maps, 4x4 PCF) and from this iteration's points on the area emitters (a cube
// each, one tap: gpu/EmitterPointLight.glsl),
// and the environment seen by rays that escape. Adds one
// sample per pixel to the accumulator (emitted and direct layers).
#include "modes/raster/RasterShared.h"
#include "shared/Brdf.h"
#include "shared/Lights.h"
#define BL_ACCUM_LAYERS kRasterAccumLayers
#include "gpu/CameraSet.glsl"
#define BL_SHADOW_SET kRasterSet
#define BL_SHADOW_BINDING kRasterBindingShadowMaps
#define BL_SHADOW_BINDING_2 kRasterBindingEmitterShadowMaps
#include "gpu/ShadowCubeLookup.glsl"
#include "gpu/ShadowedLight.glsl"
#define BL_EMITTER_POINTS_SET kRasterSet
#define BL_EMITTER_POINTS_BINDING kRasterBindingEmitterPoints
#include "gpu/EmitterPointLight.glsl"
#define BL_ENVIRONMENT_SHADOWS_SET kRasterSet
#define BL_ENVIRONMENT_SHADOWS_BINDING kRasterBindingEnvironmentShadows
#define BL_ENVIRONMENT_SHADOW_MAPS_BINDING kRasterBindingEnvironmentShadowMaps
#include "gpu/EnvironmentShadowLight.glsl"

layout(local_size_x = kRasterGroupSize, local_size_y = kRasterGroupSize) in;

layout(set = kRasterSet, binding = kRasterBindingLights) readonly buffer LightBlock { GpuLight lights[]; };
layout(push_constant) uniform PushBlock { RasterPush push; };
layout(constant_id = kRasterSpecPointLights) const bool kPointLights = true;
layout(constant_id = kRasterSpecEmitterPoints) const bool kEmitterPoints = true;
layout(constant_id = kRasterSpecEnvironment) const bool kEnvironmentShots = true;

vec3 directLight(vec3 position, vec3 n, GpuMaterial m, vec3 albedo) {
    vec3 wo = normalize(camera.position - position);
    vec3 radiance = vec3(0.0);
    for (uint i = 0u; i < push.lightCount; ++i) {
        GpuLight light = lights[i];
        vec3 wi;
        float weight;
        if (blShadowedLightWeight(light, i, push.shadowResolution, position, n, wi, weight)) {
            radiance += blEvalBrdf(m, albedo, n, wi, wo) * light.intensity * weight;
        }
    }
    return radiance;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) {
        return;
    }
    if (!blCameraHitSurface(pixel)) {
        blAccumulateLayer(pixel, kPathEmitted, blCameraBackground(pixel, push.samplePosition,
                                                                  push.environmentPresent != 0u,
                                                                  push.environmentRotation));
        return;
    }
    vec3 position = imageLoad(gbuffer[kGBufferPosition], pixel).xyz;
    vec4 normalMaterial = imageLoad(gbuffer[kGBufferNormal], pixel);
    vec3 albedo = imageLoad(gbuffer[kGBufferAlbedo], pixel).rgb;
    vec3 layers[kPathLayerCount];
    for (uint l = 0u; l < kPathLayerCount; ++l) {
        layers[l] = vec3(0.0);
    }
    layers[kPathEmitted] = imageLoad(gbuffer[kGBufferEmission], pixel).rgb;
    GpuMaterial material = materials[uint(normalMaterial.w)];
    vec3 wo = normalize(camera.position - position);
    if (kPointLights) {
        layers[kPathDirect] += directLight(position, normalMaterial.xyz, material, albedo);
    }
    if (kEmitterPoints) {
        layers[kPathDirect] += blEmitterPointsLight(position, normalMaterial.xyz, material, albedo, wo, 0.0);
    }
    if (kEnvironmentShots) {
        layers[kPathDirect] += blEnvironmentShadowLight(position, normalMaterial.xyz, material, albedo, wo, 0.0);
    }
    blAccumulate(pixel, layers);
}
