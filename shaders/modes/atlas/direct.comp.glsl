#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, point and spot lights into the atlas by cube shadow maps ([HHGM10] section 6.5: the
// bundles carry the indirect light only). One invocation per texel averages, over the texel's
// sample points (modes/atlas/TexelSamples.h, weighted by area), the irradiance of every light on
// each side of the surface (the side facing the light), 4x4 PCF visibility from the light's cube:
//   L_direct(T, side) = albedo_T / pi * sum_s w_s sum_l I_l profile_l vis cos / r^2 / sum_s w_s.
// The result is kept as its own atlas (the view's layer `direct`) and is part of every sender:
// emission + direct, so the first direction already sends it (interleaved: the update's init mode
// writes it into the sender records; bounce-by-bounce: this pass writes the sender, which sends it
// from pass 2 on, pass 1 sends the emission).
//
// Glossy pass (push.glossy, after every direction's exchange, glossy materials only): the glossy
// transfer atlas of point/spot light. Each glossy texel side adds, averaged over its samples in
// the same way, what its lobe reflects of each light toward the one of +-omega_{i+1} in the side's
// hemisphere, sum_l f_glossy(n, w_l, o) E_l, so the next direction sends the lights' glossy
// reflection too (paths light -> glossy -> ...). The geometric normal of the samples is used.
// The lights do not move while the atlas is solved, so the glossy texels' (w_l, E_l, side) per
// sample and light are kept once (the cache pass, AtlasLightRecord) and the per-direction pass
// evaluates only the lobes, one invocation per glossy texel of a list: the same sums in the same
// order, without the shadow maps' 16 lookups per sample, light and side.
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
layout(buffer_reference, std430, buffer_reference_align = 8) buffer AtlasGlossyTexels { uvec2 entries[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer AtlasLightCache { AtlasLightRecord records[]; };

// Irradiance of every point/spot light at p on the side whose normal is n.
vec3 lightAt(vec3 p, vec3 n) {
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < push.lightCount; ++i) {
        vec3 wi, light;
        if (blShadowedLight(lights[i], i, push.shadowResolution, p, n, wi, light)) {
            sum += light;
        }
    }
    return sum;
}

// lightAt averaged over the texel's sample points (weighted by area), front and back side.
void averageOverTexel(uint texel, out vec3 front, out vec3 back) {
    AtlasSamples samples = AtlasSamples(push.samples);
    AtlasFirst first = AtlasFirst(push.first);
    uint begin = first.first[texel], end = first.first[texel + 1u];
    front = vec3(0.0);
    back = vec3(0.0);
    float weights = 0.0;
    for (uint s = begin; s < end; ++s) {
        AtlasSample point = samples.samples[s];
        front += point.weight * lightAt(point.position, point.normal);
        back += point.weight * lightAt(point.position, -point.normal);
        weights += point.weight;
    }
    if (weights > 0.0) {
        front /= weights;
        back /= weights;
    }
}

void addGlossy(uint slot, vec3 value) {
    if (!any(notEqual(value, vec3(0.0)))) {
        return; // unlit side (shadow, facing away): nothing to add, the update need not visit it
    }
    blAtlasTouch(push.received, push.touched, slot);
    AtlasReceived received = AtlasReceived(push.received);
    for (uint c = 0u; c < 3u; ++c) {
        uint word = kAtlasReceivedWords * slot + kAtlasReceivedGlossy + c;
        received.words[word] = floatBitsToUint(uintBitsToFloat(received.words[word]) + value[c]);
    }
}

// Cache pass: each light at each sample of glossy texel `texel` (records from `record` on, light
// by light): the side it lights (blShadowedLight with the front normal, else with the back) and
// its direction and irradiance there.
void cacheLights(uint texel, uint record) {
    AtlasSamples samples = AtlasSamples(push.samples);
    AtlasFirst first = AtlasFirst(push.first);
    AtlasLightCache cache = AtlasLightCache(push.lightCache);
    for (uint s = first.first[texel]; s < first.first[texel + 1u]; ++s) {
        AtlasSample point = samples.samples[s];
        for (uint i = 0u; i < push.lightCount; ++i, ++record) {
            AtlasLightRecord r = AtlasLightRecord(vec3(0.0), kAtlasSides, vec3(0.0), 0u);
            if (blShadowedLight(lights[i], i, push.shadowResolution, point.position, point.normal, r.toLight,
                                r.irradiance)) {
                r.side = kAtlasFront;
            } else if (blShadowedLight(lights[i], i, push.shadowResolution, point.position, -point.normal, r.toLight,
                                       r.irradiance)) {
                r.side = kAtlasBack;
            }
            cache.records[record] = r;
        }
    }
}

// Glossy pass from the cache: averageOverTexel(glossy) of the lobes toward the one of +-next on
// each side, the lights' light read instead of looked up.
void glossyFromCache(uint texel, uint record, GpuMaterial m, out vec3 front, out vec3 back) {
    AtlasSamples samples = AtlasSamples(push.samples);
    AtlasFirst first = AtlasFirst(push.first);
    AtlasLightCache cache = AtlasLightCache(push.lightCache);
    front = vec3(0.0);
    back = vec3(0.0);
    float weights = 0.0;
    for (uint s = first.first[texel]; s < first.first[texel + 1u]; ++s) {
        AtlasSample point = samples.samples[s];
        vec3 sums[2] = vec3[2](vec3(0.0), vec3(0.0));
        for (uint i = 0u; i < push.lightCount; ++i, ++record) {
            AtlasLightRecord r = cache.records[record];
            if (r.side < kAtlasSides) {
                vec3 n = r.side == kAtlasFront ? point.normal : -point.normal;
                vec3 leaving = dot(n, push.next) >= 0.0 ? push.next : -push.next;
                sums[r.side] += blEvalBrdf(m, vec3(0.0), n, r.toLight, leaving) * r.irradiance;
            }
        }
        front += point.weight * sums[kAtlasFront];
        back += point.weight * sums[kAtlasBack];
        weights += point.weight;
    }
    if (weights > 0.0) {
        front /= weights;
        back /= weights;
    }
}

void main() {
    if (push.glossy != kAtlasDirectAtlas) {
        if (gl_GlobalInvocationID.x >= push.glossyCount) {
            return;
        }
        uvec2 entry = AtlasGlossyTexels(push.glossyTexels).entries[gl_GlobalInvocationID.x];
        if (push.glossy == kAtlasDirectGlossyCache) {
            cacheLights(entry.x, entry.y);
            return;
        }
        AtlasTexel t = AtlasTexels(push.texels).texels[entry.x];
        vec3 front, back;
        glossyFromCache(entry.x, entry.y, AtlasMaterials(push.materials).materials[t.material], front, back);
        addGlossy(kAtlasSides * entry.x + kAtlasFront, front);
        addGlossy(kAtlasSides * entry.x + kAtlasBack, back);
        return;
    }
    uint texel = gl_GlobalInvocationID.x;
    if (texel >= push.texelCount) {
        return;
    }
    AtlasTexel t = AtlasTexels(push.texels).texels[texel];
    vec3 front, back;
    averageOverTexel(texel, front, back);
    vec3 scale = t.albedo / kPi;
    AtlasRadiance direct = AtlasRadiance(push.direct);
    direct.radiance[kAtlasSides * texel + kAtlasFront] = vec4(front * scale, 0.0);
    direct.radiance[kAtlasSides * texel + kAtlasBack] = vec4(back * scale, 0.0);
    if (push.sender == uvec2(0u)) {
        return; // interleaved: the update's init mode puts direct into the sender records
    }
    AtlasRadiance sender = AtlasRadiance(push.sender);
    float into = push.directIntoSender != 0u ? 1.0 : 0.0;
    sender.radiance[kAtlasSides * texel + kAtlasFront] = vec4(t.emission + into * front * scale, 0.0);
    sender.radiance[kAtlasSides * texel + kAtlasBack] = vec4(into * back * scale, 0.0);
}
