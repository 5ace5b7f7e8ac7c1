#version 460
#extension GL_GOOGLE_include_directive : require
// Feeds known sample streams to the accumulator (tests/core/gpu/AccumulatorTest.cpp): one
// invocation per pixel adds all of a pixel's samples in a loop, so 10^5 samples take one dispatch.
#include "tests/AccumulateTest.h"
#include "shared/Random.h"
#define BL_ACCUM_SET 0
#define BL_ACCUM_BINDING 0
#define BL_ACCUM_LAYERS kAccumTestLayers
#include "gpu/Accumulate.glsl"

layout(local_size_x = kAccumTestGroupSize, local_size_y = kAccumTestGroupSize) in;
layout(push_constant) uniform PushBlock { AccumTestPush push; };

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) {
        return;
    }
    const ivec3 totalAt = ivec3(pixel, int(kAccumTotalSum));
    const float nan = uintBitsToFloat(0x7fc00000u);
    for (uint i = 0u; i < push.iterations; ++i) {
        if (push.kind == kAccumTestConstant) {
            blAccumulateLayer(pixel, kPathDirect, vec3(push.value));
        } else if (push.kind == kAccumTestPlain) {
            imageStore(blAccum, totalAt, imageLoad(blAccum, totalAt) + vec4(vec3(push.value), 1.0));
        } else if (push.kind == kAccumTestLayered) {
            vec3 layers[kPathLayerCount];
            for (uint l = 0u; l < kPathLayerCount; ++l) {
                layers[l] = vec3(0.25 * float(l + 1u));
            }
            blAccumulate(pixel, layers);
        } else if (push.kind == kAccumTestUniform) {
            uint h = blHash(blHash(uint(pixel.y) * push.width + uint(pixel.x)) ^ blHash(i + 0x9e3779b9u));
            float u = float(h >> 8) * (1.0 / 16777216.0); // 24 bits: exact in a float
            blAccumulateLayer(pixel, kPathDirect, vec3(u));
        } else if (push.kind == kAccumTestShortfall) {
            uint k = (uint(pixel.x) + i) % 5u;
            if (k == 0u) {
                blAccumulateLayer(pixel, kPathDirect, vec3(nan));
            } else if (k != 1u) {
                blAccumulateLayer(pixel, kPathDirect, vec3(1.0));
            }
        }
    }
}
