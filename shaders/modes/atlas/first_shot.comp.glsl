#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, the first shot (first_shot = auto | on; radiosity's "shoot the light sources first"):
// one invocation per texel averages, over its sample points (modes/atlas/TexelSamples.h, weighted
// by area), the irradiance this iteration's emitter points (gpu/EmitterPointLight.glsl) and
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
    vec3 irradiance[2] = vec3[2](vec3(0.0), vec3(0.0));
    float weights = 0.0;
    for (uint s = first.first[texel]; s < first.first[texel + 1u]; ++s) {
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
