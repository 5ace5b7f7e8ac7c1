#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, point and spot lights into the atlas by cube shadow maps ([HHGM10] section 6.5: the
// bundles carry the indirect light only). One invocation per texel averages, over the texel's
// sample points (modes/atlas/TexelSamples.h, weighted by area), the irradiance of every light on
// each side of the surface (the side facing the light), 4x4 PCF visibility from the light's cube:
//   L_direct(T, side) = albedo_T / pi * sum_s w_s sum_l I_l profile_l vis cos / r^2 / sum_s w_s.
// The result is kept as its own atlas (the view's layer `direct`) and starts the sender atlas:
// emission + direct, so the first direction already sends it (interleaved; bounce-by-bounce sends
// it from pass 2 on, pass 1 sends the emission).
#include "modes/atlas/AtlasBuffers.glsl"
#define BL_SHADOW_SET kAtlasDirectSet
#define BL_SHADOW_BINDING kAtlasDirectBindingShadowMaps
#include "gpu/ShadowedLight.glsl"

layout(local_size_x = kAtlasGroupSize) in;
layout(set = kAtlasDirectSet, binding = kAtlasDirectBindingLights) readonly buffer LightBlock { GpuLight lights[]; };
layout(push_constant) uniform PushBlock { AtlasDirectPush push; };

layout(buffer_reference, std430, buffer_reference_align = 16) buffer AtlasSamples { AtlasSample samples[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer AtlasFirst { uint first[]; };

// Irradiance at p on the side whose normal is n.
vec3 irradiance(vec3 p, vec3 n) {
    vec3 e = vec3(0.0);
    for (uint i = 0u; i < push.lightCount; ++i) {
        vec3 wi, light;
        if (blShadowedLight(lights[i], i, push.shadowResolution, p, n, wi, light)) {
            e += light;
        }
    }
    return e;
}

void main() {
    uint texel = gl_GlobalInvocationID.x;
    if (texel >= push.texelCount) {
        return;
    }
    AtlasSamples samples = AtlasSamples(push.samples);
    AtlasFirst first = AtlasFirst(push.first);
    uint begin = first.first[texel], end = first.first[texel + 1u];
    vec3 front = vec3(0.0), back = vec3(0.0);
    float weights = 0.0;
    for (uint s = begin; s < end; ++s) {
        AtlasSample point = samples.samples[s];
        front += point.weight * irradiance(point.position, point.normal);
        back += point.weight * irradiance(point.position, -point.normal);
        weights += point.weight;
    }
    AtlasTexel t = AtlasTexels(push.texels).texels[texel];
    vec3 scale = weights > 0.0 ? t.albedo / (kPi * weights) : vec3(0.0);
    AtlasRadiance direct = AtlasRadiance(push.direct);
    direct.radiance[kAtlasSides * texel + kAtlasFront] = vec4(front * scale, 0.0);
    direct.radiance[kAtlasSides * texel + kAtlasBack] = vec4(back * scale, 0.0);
    AtlasRadiance sender = AtlasRadiance(push.sender);
    float into = push.directIntoSender != 0u ? 1.0 : 0.0;
    sender.radiance[kAtlasSides * texel + kAtlasFront] = vec4(t.emission + into * front * scale, 0.0);
    sender.radiance[kAtlasSides * texel + kAtlasBack] = vec4(into * back * scale, 0.0);
}
