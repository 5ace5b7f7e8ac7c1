#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, the first shot (first_shot = auto | on; radiosity's "shoot the light sources first"):
// one invocation per texel averages, over its sample points (modes/atlas/TexelSamples.h, weighted
// by area), the irradiance this iteration's emitter points give each side of the surface
// (gpu/EmitterPointLight.glsl), as the direct pass does for point lights:
//   L_shot(T, side) = albedo_T / pi * sum_s w_s E_points(s, side) / sum_s w_s,
// adds it to the side's running sum (which the environment's shot, environment_shot.comp.glsl, has
// added this iteration's environment light to before), and writes the direct atlas (point/spot part
// + the sum's mean over the iterations so far, an unbiased estimate of the emitters' and the
// environment's direct light) and the sender record's constant part (the same, with no emission:
// the exchange then carries reflected light only, the direct light having been shot). Without
// area emitters there are no points and only the sum's mean is written.
#include "modes/atlas/AtlasBuffers.glsl"
#define BL_SHADOW_SET kAtlasFirstShotSet
#define BL_SHADOW_BINDING kAtlasFirstShotBindingMaps
#define BL_SHADOW_BINDING_2 kAtlasFirstShotBindingMaps2
#include "gpu/ShadowCubeLookup.glsl"
#define BL_EMITTER_POINTS_SET kAtlasFirstShotSet
#define BL_EMITTER_POINTS_BINDING kAtlasFirstShotBindingPoints
#include "gpu/EmitterPointLight.glsl"

layout(local_size_x = kAtlasGroupSize) in;
layout(push_constant) uniform PushBlock { AtlasFirstShotPush push; };

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
        irradiance[kAtlasFront] += point.weight * blEmitterPointsIrradiance(point.position, point.normal);
        irradiance[kAtlasBack] += point.weight * blEmitterPointsIrradiance(point.position, -point.normal);
        weights += point.weight;
    }
    vec3 scale = AtlasTexels(push.texels).texels[texel].albedo / kPi / max(weights, 1e-30);
    AtlasRadiance sums = AtlasRadiance(push.shotSum);
    AtlasRadiance direct = AtlasRadiance(push.direct);
    AtlasRadiance pointDirect = AtlasRadiance(push.pointDirect);
    AtlasSenders senders = AtlasSenders(push.senders);
    for (uint side = 0u; side < kAtlasSides; ++side) {
        uint slot = kAtlasSides * texel + side;
        vec3 sum = sums.radiance[slot].rgb + (weights > 0.0 ? irradiance[side] * scale : vec3(0.0));
        sums.radiance[slot] = vec4(sum, 0.0);
        vec3 d = pointDirect.radiance[slot].rgb + sum * push.inverseShots;
        direct.radiance[slot] = vec4(d, 0.0);
        senders.records[slot].base = d;
    }
}
