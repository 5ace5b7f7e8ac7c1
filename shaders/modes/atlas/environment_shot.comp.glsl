#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, the environment's first shot (environment_shots = K > 0; AtlasShared.h): this
// iteration's K directions drawn by the environment's importance, each with its depth map
// (bundle/EnvironmentShadowPass.h, gpu/EnvironmentShadowLight.glsl). One invocation per texel
// averages, over its sample points (weighted by area, as the emitter points' shot and the direct
// pass do), the irradiance they give each side, and adds
//   albedo_T / pi * sum_s w_s E_env(s, side) / sum_s w_s
// to that side's running sum of shots: one unbiased estimate of the environment's direct light per
// iteration (up to the maps' contact strips), which first_shot.comp.glsl turns into the direct atlas.
#include "modes/atlas/AtlasBuffers.glsl"
#define BL_ENVIRONMENT_SHADOWS_SET kAtlasEnvironmentShotSet
#define BL_ENVIRONMENT_SHADOWS_BINDING kAtlasEnvironmentShotBindingShadows
#define BL_ENVIRONMENT_SHADOW_MAPS_BINDING kAtlasEnvironmentShotBindingMaps
#include "gpu/EnvironmentShadowLight.glsl"

layout(local_size_x = kAtlasGroupSize) in;
layout(push_constant) uniform PushBlock { AtlasEnvironmentShotPush push; };

layout(buffer_reference, std430, buffer_reference_align = 16) buffer AtlasShotSamples { AtlasSample samples[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer AtlasShotFirst { uint first[]; };

void main() {
    uint texel = gl_GlobalInvocationID.x;
    if (texel >= push.texelCount) {
        return;
    }
    AtlasShotSamples samples = AtlasShotSamples(push.samples);
    AtlasShotFirst first = AtlasShotFirst(push.first);
    vec3 irradiance[2] = vec3[2](vec3(0.0), vec3(0.0));
    float weights = 0.0;
    for (uint s = first.first[texel]; s < first.first[texel + 1u]; ++s) {
        AtlasSample point = samples.samples[s];
        irradiance[kAtlasFront] += point.weight * blEnvironmentShadowIrradiance(point.position, point.normal);
        irradiance[kAtlasBack] += point.weight * blEnvironmentShadowIrradiance(point.position, -point.normal);
        weights += point.weight;
    }
    if (!(weights > 0.0)) {
        return;
    }
    vec3 scale = AtlasTexels(push.texels).texels[texel].albedo / kPi / weights;
    AtlasRadiance sums = AtlasRadiance(push.shotSum);
    for (uint side = 0u; side < kAtlasSides; ++side) {
        uint slot = kAtlasSides * texel + side;
        sums.radiance[slot] = vec4(sums.radiance[slot].rgb + irradiance[side] * scale, 0.0);
    }
}
