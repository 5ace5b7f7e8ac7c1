#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, the glossy highlight of point and spot lights toward the eye, per camera pixel of
// one view sample: sum over lights of f_glossy(n, wi, eye) E_l (E_l: the light's irradiance with
// cube shadow-map visibility, ShadowedLight.glsl, as the direct pass lights the atlas). Their
// Lambert part is the direct atlas; the shade pass adds this to layer `direct`.
#include "modes/atlas/AtlasBuffers.glsl"
#define BL_ACCUM_LAYERS kAtlasAccumLayers
#include "gpu/CameraSet.glsl"
#define BL_SHADOW_SET kAtlasHighlightLightSet
#define BL_SHADOW_BINDING kAtlasDirectBindingShadowMaps
#include "gpu/ShadowedLight.glsl"
#include "shared/Brdf.h"
#include "modes/atlas/GlossyPixel.glsl"

layout(local_size_x = kAtlasViewGroupSize, local_size_y = kAtlasViewGroupSize) in;
layout(set = kAtlasHighlightLightSet, binding = kAtlasDirectBindingLights) readonly buffer LightBlock { GpuLight lights[]; };
layout(push_constant) uniform PushBlock { AtlasHighlightPush push; };

vec3 highlight(ivec2 pixel) {
    GpuMaterial m;
    vec3 p, n, eye;
    if (!blAtlasGlossyPixel(pixel, m, p, n, eye)) {
        return vec3(0.0);
    }
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < push.lightCount; ++i) {
        vec3 wi, irradiance;
        if (blShadowedLight(lights[i], i, push.shadowResolution, p, n, wi, irradiance)) {
            sum += blEvalBrdf(m, vec3(0.0), n, wi, eye) * irradiance;
        }
    }
    return sum;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) {
        return;
    }
    AtlasRadiance(push.highlight).radiance[uint(pixel.y) * push.width + uint(pixel.x)] = vec4(highlight(pixel), 0.0);
}
