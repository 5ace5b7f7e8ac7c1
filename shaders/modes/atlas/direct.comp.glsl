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
//
// Glossy pass (push.glossy, after every direction's exchange, glossy materials only): the glossy
// transfer atlas of point/spot light. Each glossy texel side adds, averaged over its samples in
// the same way, what its lobe reflects of each light toward the one of +-omega_{i+1} in the side's
// hemisphere, sum_l f_glossy(n, w_l, o) E_l, so the next direction sends the lights' glossy
// reflection too (paths light -> glossy -> ...). The geometric normal of the samples is used.
#include "modes/atlas/AtlasBuffers.glsl"
#include "shared/Brdf.h"
#define BL_SHADOW_SET kAtlasDirectSet
#define BL_SHADOW_BINDING kAtlasDirectBindingShadowMaps
#include "gpu/ShadowedLight.glsl"

layout(local_size_x = kAtlasGroupSize) in;
layout(set = kAtlasDirectSet, binding = kAtlasDirectBindingLights) readonly buffer LightBlock { GpuLight lights[]; };
layout(push_constant) uniform PushBlock { AtlasDirectPush push; };

layout(buffer_reference, std430, buffer_reference_align = 16) buffer AtlasSamples { AtlasSample samples[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer AtlasFirst { uint first[]; };

// Light of every point/spot light at p on the side whose normal is n: the irradiance, or with
// `glossy` what material m's lobe reflects of it toward the one of +-next on n's side.
vec3 lightAt(vec3 p, vec3 n, GpuMaterial m, bool glossy) {
    vec3 leaving = dot(n, push.next) >= 0.0 ? push.next : -push.next;
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < push.lightCount; ++i) {
        vec3 wi, light;
        if (blShadowedLight(lights[i], i, push.shadowResolution, p, n, wi, light)) {
            sum += glossy ? blEvalBrdf(m, vec3(0.0), n, wi, leaving) * light : light; // albedo 0: the lobe alone
        }
    }
    return sum;
}

// lightAt averaged over the texel's sample points (weighted by area), front and back side.
void averageOverTexel(uint texel, GpuMaterial m, bool glossy, out vec3 front, out vec3 back) {
    AtlasSamples samples = AtlasSamples(push.samples);
    AtlasFirst first = AtlasFirst(push.first);
    uint begin = first.first[texel], end = first.first[texel + 1u];
    front = vec3(0.0);
    back = vec3(0.0);
    float weights = 0.0;
    for (uint s = begin; s < end; ++s) {
        AtlasSample point = samples.samples[s];
        front += point.weight * lightAt(point.position, point.normal, m, glossy);
        back += point.weight * lightAt(point.position, -point.normal, m, glossy);
        weights += point.weight;
    }
    if (weights > 0.0) {
        front /= weights;
        back /= weights;
    }
}

void addGlossy(uint slot, vec3 value) {
    AtlasReceived received = AtlasReceived(push.received);
    for (uint c = 0u; c < 3u; ++c) {
        uint word = kAtlasReceivedWords * slot + kAtlasReceivedGlossy + c;
        received.words[word] = floatBitsToUint(uintBitsToFloat(received.words[word]) + value[c]);
    }
}

void main() {
    uint texel = gl_GlobalInvocationID.x;
    if (texel >= push.texelCount) {
        return;
    }
    AtlasTexel t = AtlasTexels(push.texels).texels[texel];
    vec3 front, back;
    if (push.glossy != 0u) {
        GpuMaterial m = AtlasMaterials(push.materials).materials[t.material];
        if (t.inverseArea > 0.0 && m.specular.x + m.specular.y + m.specular.z > 0.0) {
            averageOverTexel(texel, m, true, front, back);
            addGlossy(kAtlasSides * texel + kAtlasFront, front);
            addGlossy(kAtlasSides * texel + kAtlasBack, back);
        }
        return;
    }
    GpuMaterial none = GpuMaterial(vec3(0.0), 0u, vec3(0.0), 1.0, 1.0, 0u, 0u, 0u); // unused: not glossy
    averageOverTexel(texel, none, false, front, back);
    vec3 scale = t.albedo / kPi;
    AtlasRadiance direct = AtlasRadiance(push.direct);
    direct.radiance[kAtlasSides * texel + kAtlasFront] = vec4(front * scale, 0.0);
    direct.radiance[kAtlasSides * texel + kAtlasBack] = vec4(back * scale, 0.0);
    AtlasRadiance sender = AtlasRadiance(push.sender);
    float into = push.directIntoSender != 0u ? 1.0 : 0.0;
    sender.radiance[kAtlasSides * texel + kAtlasFront] = vec4(t.emission + into * front * scale, 0.0);
    sender.radiance[kAtlasSides * texel + kAtlasBack] = vec4(into * back * scale, 0.0);
}
