#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, camera view: per pixel, the emitted radiance seen (G-buffer, front faces only), the
// environment behind the scene, and the reflected radiance of the atlas texel side the camera sees
// (weighted sum over directions / total weight, layer `rest`; point/spot light of the direct pass,
// layer `direct`), bilinear between texel centres inside the chart; where the mode has glossy
// materials, the final glossy gather (gather.comp.glsl: per pixel over the directions, to `rest`)
// and the point/spot lights' glossy highlight of this sample (highlight.comp.glsl, to `direct`).
#include "modes/atlas/AtlasBuffers.glsl"
#define BL_ACCUM_LAYERS kAtlasAccumLayers
#include "gpu/CameraSet.glsl"

layout(local_size_x = kAtlasViewGroupSize, local_size_y = kAtlasViewGroupSize) in;
layout(set = kAtlasViewSet, binding = kAtlasViewBinding, rgba32f) uniform readonly image2D viewImage;
layout(push_constant) uniform PushBlock { AtlasShadePush push; };

// Index of texel `texel` of `page`.
uint indexOf(ivec2 texel, uint page) { return (page * push.atlasHeight + uint(texel.y)) * push.atlasWidth + uint(texel.x); }

// Adds w times a texel side's reflected radiance: the exchange's weighted mean and the direct
// pass's point and spot light.
// Split channels (delay_indirect): the one-bounce estimate is light of two segments, so it joins
// `direct` (as the reference's layers count), the multi-bounce estimate `rest`.
void reflectedAt(uint index, uint side, float w, inout vec3 exchanged, inout vec3 direct) {
    uint slot = kAtlasSides * index + side;
    AtlasRadiance sums = AtlasRadiance(push.sums);
    vec3 mean = (sums.radiance[2u * slot].rgb + sums.radiance[2u * slot + 1u].rgb) * push.reflectedScale;
    if (push.split != 0u) {
        AtlasRadiance indirect = AtlasRadiance(push.sumsIndirect);
        exchanged += w * (indirect.radiance[2u * slot].rgb + indirect.radiance[2u * slot + 1u].rgb) * push.indirectScale;
        direct += w * (mean + AtlasRadiance(push.direct).radiance[slot].rgb);
        return;
    }
    exchanged += w * (mean + AtlasRadiance(push.settled).radiance[slot].rgb);
    direct += w * push.directScale * AtlasRadiance(push.direct).radiance[slot].rgb;
}

bool usable(ivec2 texel, uint page, int chart) {
    if (texel.x < 0 || texel.y < 0 || texel.x >= int(push.atlasWidth) || texel.y >= int(push.atlasHeight)) {
        return false;
    }
    uint index = indexOf(texel, page);
    return AtlasCharts(push.charts).charts[index] == chart && AtlasTexels(push.texels).texels[index].inverseArea > 0.0;
}

// The exchanged and the direct reflected radiance at atlas uv of `page`, side `side`.
void reflected(vec2 uv, uint page, uint side, out vec3 exchanged, out vec3 direct) {
    exchanged = vec3(0.0);
    direct = vec3(0.0);
    vec2 size = vec2(push.atlasWidth, push.atlasHeight);
    ivec2 nearest = clamp(ivec2(floor(uv * size)), ivec2(0), ivec2(size) - 1);
    if (push.bilinear == 0u) {
        reflectedAt(indexOf(nearest, page), side, 1.0, exchanged, direct);
        return;
    }
    // Bilinear between the four texel centres around uv, over those of the same chart that hold
    // surface (weights renormalized): no light from a neighbouring chart or an empty texel.
    int chart = AtlasCharts(push.charts).charts[indexOf(nearest, page)];
    vec2 p = uv * size - 0.5;
    ivec2 base = ivec2(floor(p));
    vec2 f = p - vec2(base);
    float weights = 0.0;
    for (int dy = 0; dy <= 1; ++dy) {
        for (int dx = 0; dx <= 1; ++dx) {
            ivec2 t = base + ivec2(dx, dy);
            float w = (dx == 1 ? f.x : 1.0 - f.x) * (dy == 1 ? f.y : 1.0 - f.y);
            if (w > 0.0 && usable(t, page, chart)) {
                reflectedAt(indexOf(t, page), side, w, exchanged, direct);
                weights += w;
            }
        }
    }
    if (weights > 0.0) {
        exchanged /= weights;
        direct /= weights;
    } else {
        reflectedAt(indexOf(nearest, page), side, 1.0, exchanged, direct);
    }
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) {
        return;
    }
    vec3 layers[kPathLayerCount];
    for (uint l = 0u; l < kPathLayerCount; ++l) {
        layers[l] = vec3(0.0);
    }
    vec4 view = imageLoad(viewImage, pixel);
    uint index = uint(pixel.y) * push.width + uint(pixel.x);
    if (!blCameraHitSurface(pixel) || view.w == 0.0) {
        layers[kPathEmitted] = blCameraBackground(pixel, push.samplePosition, push.environmentPresent != 0u,
                                                  push.environmentRotation);
    } else {
        layers[kPathEmitted] = imageLoad(gbuffer[kGBufferEmission], pixel).rgb;
        reflected(view.xy, uint(view.z), uint(view.w) - 1u, layers[kPathRest], layers[kPathDirect]);
        if (push.highlight != uvec2(0u)) {
            layers[kPathDirect] += AtlasRadiance(push.highlight).radiance[index].rgb;
        }
    }
    // The gather's per-pixel mean already averages its own jittered samples (escaped ones gave 0).
    if (push.gathered != uvec2(0u)) {
        vec3 gathered = push.reflectedScale * AtlasRadiance(push.gathered).radiance[index].rgb;
        if (push.split != 0u) {
            layers[kPathDirect] += gathered;
            layers[kPathRest] += push.indirectScale * AtlasRadiance(push.gatheredIndirect).radiance[index].rgb;
        } else {
            layers[kPathRest] += gathered;
        }
    }
    blAccumulate(pixel, layers);
}
