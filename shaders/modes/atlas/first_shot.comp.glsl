#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, the first shot (first_shot = auto | on; radiosity's "shoot the light sources first"):
// one invocation per texel averages, over its sample points (modes/atlas/TexelSamples.h, weighted
// by area; shot_samples = one: one of them drawn by that weight, an unbiased estimate of the
// mean), the irradiance this iteration's emitter points (gpu/EmitterPointLight.glsl) and
// environment directions (gpu/EnvironmentShadowLight.glsl: a depth map each) give each side of the
// surface, as the direct pass does for point lights:
//   L_shot(T, side) = albedo_T / pi * sum_s w_s (E_points(s, side) + E_environment(s, side)) / sum_s w_s,
// adds it to the side's running sum, and writes the direct atlas (point/spot part + the sum's mean
// over the iterations so far, an unbiased estimate of the emitters' and the environment's direct
// light, up to the depth maps' contact strips) and the sender record's constant part (the same,
// with no emission: the exchange then carries reflected light only, the direct light having been
// shot; its list ends receive nothing where the environment was shot). A part whose source the
// scene lacks has no points or directions and adds nothing.
#include "modes/atlas/AtlasBuffers.glsl"
#include "shared/Random.h"
#define BL_SHADOW_SET kAtlasFirstShotSet
#define BL_SHADOW_BINDING kAtlasFirstShotBindingMaps
#define BL_SHADOW_BINDING_2 kAtlasFirstShotBindingMaps2
#include "gpu/ShadowCubeLookup.glsl"
#define BL_EMITTER_POINTS_SET kAtlasFirstShotSet
#define BL_EMITTER_POINTS_BINDING kAtlasFirstShotBindingPoints
#include "gpu/EmitterPointLight.glsl"
#define BL_ENVIRONMENT_SHADOWS_SET kAtlasFirstShotSet
#define BL_ENVIRONMENT_SHADOWS_BINDING kAtlasFirstShotBindingEnvironment
#define BL_ENVIRONMENT_SHADOW_MAPS_BINDING kAtlasFirstShotBindingEnvironmentMaps
#include "gpu/EnvironmentShadowLight.glsl"

layout(local_size_x = kAtlasGroupSize) in;
layout(constant_id = kAtlasShotSpecAllSamples) const bool kAllSamples = false;
layout(push_constant) uniform PushBlock { AtlasFirstShotPush push; };

layout(buffer_reference, std430, buffer_reference_align = 16) buffer AtlasShotSamples { AtlasSample samples[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer AtlasShotFirst { uint first[]; };

void main() {
    uint texel = gl_GlobalInvocationID.x;
    // A texel no surface maps to is never hit, read or seen: nothing to write (its direct and sum
    // words stay zero, its sender record what the init pass wrote: none of it is read).
    if (texel >= push.texelCount || !(AtlasTexels(push.texels).texels[texel].inverseArea > 0.0)) {
        return;
    }
    AtlasShotSamples samples = AtlasShotSamples(push.samples);
    AtlasShotFirst first = AtlasShotFirst(push.first);
    uint begin = first.first[texel];
    uint end = first.first[texel + 1u];
    if (!kAllSamples) {
        // shot_samples = one: the sample s drawn with probability w_s / sum w, so its light alone
        // is an unbiased estimate of the weighted mean the loop below forms over all of them. Each
        // texel rotates a golden-ratio sequence over the shots (its start hashed from the texel and
        // the seed): consecutive shots spread over the texel's surface as the grid does.
        float total = 0.0;
        for (uint s = begin; s < end; ++s) total += samples.samples[s].weight;
        uint rotation = blHash(texel ^ push.seedHash) + push.shot * 2654435769u;
        float target = float(rotation >> 8u) * (1.0 / 16777216.0) * total;
        // The sample whose cumulative weight passes the target (it has weight, or the sum would
        // not have moved past the target); where rounding leaves the target at the total, the
        // last sample with any weight. None has weight: none is lit, as with every sample.
        float below = 0.0;
        uint chosen = end;
        for (uint s = begin; s < end; ++s) {
            float w = samples.samples[s].weight;
            chosen = w > 0.0 ? s : chosen;
            below += w;
            if (target < below) {
                break;
            }
        }
        begin = chosen;
        end = min(chosen + 1u, end);
    }
    vec3 irradiance[2] = vec3[2](vec3(0.0), vec3(0.0));
    float weights = 0.0;
    for (uint s = begin; s < end; ++s) {
        AtlasSample point = samples.samples[s];
        vec3 front, back, pointsFront, pointsBack;
        blEnvironmentShadowIrradianceBothSides(point.position, point.normal, front, back);
        blEmitterPointsIrradianceBothSides(point.position, point.normal, pointsFront, pointsBack);
        irradiance[kAtlasFront] += point.weight * (pointsFront + front);
        irradiance[kAtlasBack] += point.weight * (pointsBack + back);
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
