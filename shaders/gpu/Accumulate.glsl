// Adds one sample per pixel to the layered accumulator (core/gpu/Accumulator.h). Include after
// defining BL_ACCUM_SET and BL_ACCUM_BINDING (where the mode binds Accumulator::view()) and
// BL_ACCUM_LAYERS (the mode's layer mask, the same constant the host gives the Accumulator).
//
// Sums are compensated (Neumaier's variant of Kahan summation) in a second slot: plain float sums
// drift by ~1e-4 relative after 10^5 additions, these stay within a few ulp. `precise` keeps the
// compiler from simplifying the compensation away (SPIR-V NoContraction, exact in Mesa's NIR).
// One invocation owns each pixel: read-modify-write without atomics.
#ifndef BL_GPU_ACCUMULATE_GLSL
#define BL_GPU_ACCUMULATE_GLSL
#include "shared/Accumulation.h"

layout(set = BL_ACCUM_SET, binding = BL_ACCUM_BINDING, rgba32f) uniform image2DArray blAccum;

// sum += x with the running error in `error` (both rgb; w untouched).
void blCompensatedAdd(ivec2 pixel, uint sumSlot, vec3 x, float sumW, float errorW) {
    precise vec4 sum = imageLoad(blAccum, ivec3(pixel, int(sumSlot)));
    precise vec4 error = imageLoad(blAccum, ivec3(pixel, int(sumSlot + 1u)));
    precise vec3 t = sum.xyz + x;
    bvec3 sumBigger = greaterThanEqual(abs(sum.xyz), abs(x));
    precise vec3 lost = mix((x - t) + sum.xyz, (sum.xyz - t) + x, sumBigger);
    precise vec3 newError = error.xyz + lost;
    imageStore(blAccum, ivec3(pixel, int(sumSlot)), vec4(t, sum.w + sumW));
    imageStore(blAccum, ivec3(pixel, int(sumSlot + 1u)), vec4(newError, error.w + errorW));
}

// Adds one sample split by path length (entries of layers absent from BL_ACCUM_LAYERS are ignored).
// A sample with any NaN/Inf is refused as a whole and counted as non-finite.
void blAccumulate(ivec2 pixel, vec3 layers[kPathLayerCount]) {
    vec3 total = vec3(0.0);
    for (uint l = 0u; l < kPathLayerCount; ++l) {
        if ((BL_ACCUM_LAYERS & (1u << l)) != 0u) {
            total += layers[l];
        }
    }
    if (any(isnan(total)) || any(isinf(total))) {
        vec4 error = imageLoad(blAccum, ivec3(pixel, int(kAccumTotalError)));
        imageStore(blAccum, ivec3(pixel, int(kAccumTotalError)), error + vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    blCompensatedAdd(pixel, kAccumTotalSum, total, 1.0, 0.0);
    blCompensatedAdd(pixel, kAccumSquareSum, total * total, 0.0, 0.0);
    for (uint l = 0u; l < kPathLayerCount; ++l) {
        if ((BL_ACCUM_LAYERS & (1u << l)) != 0u) {
            blCompensatedAdd(pixel, blAccumLayerSlot(BL_ACCUM_LAYERS, l), layers[l], 0.0, 0.0);
        }
    }
}

// A sample of a single layer.
void blAccumulateLayer(ivec2 pixel, uint layer, vec3 radiance) {
    vec3 layers[kPathLayerCount];
    for (uint l = 0u; l < kPathLayerCount; ++l) {
        layers[l] = l == layer ? radiance : vec3(0.0);
    }
    blAccumulate(pixel, layers);
}

#endif
