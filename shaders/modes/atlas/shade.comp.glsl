#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, camera view: per pixel, the emitted radiance seen (G-buffer, front faces only), the
// environment behind the scene, and the reflected radiance of the atlas texel side the camera sees
// (weighted sum over directions / total weight), bilinear between texel centres inside the chart.
#include "modes/atlas/AtlasBuffers.glsl"
#define BL_ACCUM_LAYERS kAtlasAccumLayers
#include "gpu/CameraSet.glsl"

layout(local_size_x = kAtlasViewGroupSize, local_size_y = kAtlasViewGroupSize) in;
layout(set = kAtlasViewSet, binding = kAtlasViewBinding, rgba32f) uniform readonly image2D viewImage;
layout(push_constant) uniform PushBlock { AtlasShadePush push; };

vec3 reflectedAt(ivec2 texel, uint page, uint side) {
    uint index = (page * push.atlasHeight + uint(texel.y)) * push.atlasWidth + uint(texel.x);
    uint slot = kAtlasSides * index + side;
    AtlasRadiance sums = AtlasRadiance(push.sums);
    return (sums.radiance[2u * slot].rgb + sums.radiance[2u * slot + 1u].rgb) * push.reflectedScale;
}

bool usable(ivec2 texel, uint page, int chart) {
    if (texel.x < 0 || texel.y < 0 || texel.x >= int(push.atlasWidth) || texel.y >= int(push.atlasHeight)) {
        return false;
    }
    uint index = (page * push.atlasHeight + uint(texel.y)) * push.atlasWidth + uint(texel.x);
    return AtlasCharts(push.charts).charts[index] == chart && AtlasTexels(push.texels).texels[index].inverseArea > 0.0;
}

vec3 reflected(vec2 uv, uint page, uint side) {
    if (push.reflectedScale == 0.0) {
        return vec3(0.0);
    }
    vec2 size = vec2(push.atlasWidth, push.atlasHeight);
    ivec2 nearest = clamp(ivec2(floor(uv * size)), ivec2(0), ivec2(size) - 1);
    if (push.bilinear == 0u) {
        return reflectedAt(nearest, page, side);
    }
    // Bilinear between the four texel centres around uv, over those of the same chart that hold
    // surface (weights renormalized): no light from a neighbouring chart or an empty texel.
    int chart = AtlasCharts(push.charts).charts[(page * push.atlasHeight + uint(nearest.y)) * push.atlasWidth +
                                               uint(nearest.x)];
    vec2 p = uv * size - 0.5;
    ivec2 base = ivec2(floor(p));
    vec2 f = p - vec2(base);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int dy = 0; dy <= 1; ++dy) {
        for (int dx = 0; dx <= 1; ++dx) {
            ivec2 t = base + ivec2(dx, dy);
            float w = (dx == 1 ? f.x : 1.0 - f.x) * (dy == 1 ? f.y : 1.0 - f.y);
            if (w > 0.0 && usable(t, page, chart)) {
                sum += w * reflectedAt(t, page, side);
                weights += w;
            }
        }
    }
    return weights > 0.0 ? sum / weights : reflectedAt(nearest, page, side);
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
    if (!blCameraHitSurface(pixel) || view.w == 0.0) {
        layers[kPathEmitted] = blCameraBackground(pixel, push.samplePosition, push.environmentPresent != 0u,
                                                  push.environmentRotation);
    } else {
        layers[kPathEmitted] = imageLoad(gbuffer[kGBufferEmission], pixel).rgb;
        layers[kPathRest] = reflected(view.xy, uint(view.z), uint(view.w) - 1u);
    }
    blAccumulate(pixel, layers);
}
