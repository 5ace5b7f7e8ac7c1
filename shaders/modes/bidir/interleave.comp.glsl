#version 460
#extension GL_GOOGLE_include_directive : require
// Mode bidir, after the evaluation: geometry-aware blur of the interleaved indirect light over each
// pixel's n x n neighbourhood ([TO12s] A.1), then, with temporal interleaving, the cache update and
// the reconstruction from the 2 x 2 sub-pixel caches by reverse reprojection ([TO12s] A.2, Eq. 1
// and 3), and the pixel's sample added to the accumulator. Layers emitted and direct pass through
// unfiltered and uncached (direct light is high-frequency, [TO12s] B.1). Definitions in
// modes/bidir/Interleave.h.
#include "modes/bidir/BidirShared.h"
#include "modes/bidir/Interleave.h"
#define BL_ACCUM_LAYERS kBidirAccumLayers
#include "gpu/CameraSet.glsl"

layout(local_size_x = kInterleaveGroupSize, local_size_y = kInterleaveGroupSize) in;

layout(set = kInterleaveSet, binding = kInterleaveBindingFrame, rgba32f) uniform readonly image2DArray frameLayers;
layout(set = kInterleaveSet, binding = kInterleaveBindingCaches, rgba32f) uniform image2DArray caches;
layout(set = kInterleaveSet, binding = kInterleaveBindingCameras) readonly buffer CacheBlock {
    InterleaveCache cacheInfo[];
};
layout(push_constant) uniform PushBlock { InterleavePush push; };

bool evaluated(ivec2 p) { return imageLoad(frameLayers, ivec3(p, 0)).w == kFrameWritten; }

// The blur's geometry weight of neighbour (xq, nq) for the pixel's point x (normal n, depth z).
float geometryWeight(vec3 x, vec3 n, float z, vec3 xq, vec3 nq) {
    float plane = dot(xq - x, n) / (kFilterPlaneScale * z);
    return pow(max(dot(n, nq), 0.0), kFilterNormalPower) * exp(-plane * plane);
}

// Where world point x lands in cache camera c: the pixel whose footprint holds it (cache texel q
// holds the sample at q + its sub-pixel, so for a static camera q is the pixel itself).
bool reprojectInto(GpuCamera c, vec3 x, float z, out ivec2 q) {
    vec3 v = x - c.position;
    vec2 s = vec2(dot(v, c.right) / (z * c.tanHalfX), dot(v, c.up) / (z * c.tanHalfY));
    vec2 p = vec2((s.x + 1.0) * 0.5 * c.width, (1.0 - s.y) * 0.5 * c.height);
    q = ivec2(floor(p));
    return q.x >= 0 && q.y >= 0 && q.x < int(push.width) && q.y < int(push.height);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height) || !evaluated(pixel)) {
        return; // outside, or the evaluation dropped the sample: nothing is added
    }
    vec3 layers[kPathLayerCount];
    for (uint l = 0u; l < kPathLayerCount; ++l) {
        layers[l] = imageLoad(frameLayers, ivec3(pixel, int(l))).rgb;
    }
    bool surface = blCameraHitSurface(pixel);
    vec3 x = imageLoad(gbuffer[kGBufferPosition], pixel).xyz;
    float z = blTemporalViewDepth(camera, x);
    if (surface && push.blur != 0u && push.interleave > 1u) {
        vec3 n = imageLoad(gbuffer[kGBufferNormal], pixel).xyz;
        int r = int(push.interleave / 2u);
        vec3 sum1 = vec3(0.0), sum2 = vec3(0.0);
        float weights = 0.0;
        for (int dy = -r; dy <= r; ++dy) {
            for (int dx = -r; dx <= r; ++dx) {
                ivec2 q = pixel + ivec2(dx, dy);
                if (q.x < 0 || q.y < 0 || q.x >= int(push.width) || q.y >= int(push.height) || !evaluated(q) ||
                    !blCameraHitSurface(q)) {
                    continue;
                }
                float w = blInterleaveTap(dx, push.interleave) * blInterleaveTap(dy, push.interleave) *
                          geometryWeight(x, n, z, imageLoad(gbuffer[kGBufferPosition], q).xyz,
                                         imageLoad(gbuffer[kGBufferNormal], q).xyz);
                sum1 += w * imageLoad(frameLayers, ivec3(q, int(kPathIndirect1))).rgb;
                sum2 += w * imageLoad(frameLayers, ivec3(q, int(kPathIndirect2))).rgb;
                weights += w;
            }
        }
        // The pixel itself has weight >= 1/4 (its own normal and plane), so weights > 0.
        layers[kPathIndirect1] = sum1 / weights;
        layers[kPathIndirect2] = sum2 / weights;
    }
    if (push.temporal != 0u) {
        // This frame's cache: z = 0 marks a pixel whose sample saw no surface.
        int c = int(push.cache);
        imageStore(caches, ivec3(pixel, 2 * c), vec4(layers[kPathIndirect1], surface ? z : 0.0));
        imageStore(caches, ivec3(pixel, 2 * c + 1), vec4(layers[kPathIndirect2], 0.0));
        float hits = 0.0; // the other caches' weights: the cache-hit image
        if (surface) {
            // Eq. 1: L = sum_i h_i L_i(gamma_i(s)) / sum_i h_i, the current cache with h = 1.
            vec3 sum1 = layers[kPathIndirect1], sum2 = layers[kPathIndirect2];
            float weights = 1.0;
            for (uint i = 0u; i < kTemporalCaches; ++i) {
                if (i == push.cache || cacheInfo[i].valid == 0u) {
                    continue;
                }
                GpuCamera ci = cacheInfo[i].camera;
                float zi = blTemporalViewDepth(ci, x);
                ivec2 q = pixel; // static camera: gamma_i is the identity
                if (!(zi > 0.0) || (push.reproject != 0u && !reprojectInto(ci, x, zi, q))) {
                    continue;
                }
                vec4 cached = imageLoad(caches, ivec3(q, int(2u * i)));
                if (!(cached.w > 0.0)) {
                    continue;
                }
                float h = blTemporalDepthWeight(zi, cached.w, push.twoSigma2);
                sum1 += h * cached.rgb;
                sum2 += h * imageLoad(caches, ivec3(q, int(2u * i + 1u))).rgb;
                weights += h;
                hits += h;
            }
            layers[kPathIndirect1] = sum1 / weights;
            layers[kPathIndirect2] = sum2 / weights;
        }
        imageStore(caches, ivec3(pixel, int(kTemporalHitsLayer)), vec4(hits / float(kTemporalCaches - 1u), 0.0, 0.0, 0.0));
    }
    blAccumulate(pixel, layers);
}
