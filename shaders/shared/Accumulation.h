// Layered progressive accumulation (core/gpu/Accumulator.h, shaders/gpu/Accumulate.glsl): the
// path-length layers the CPU reference reports (core/reference/PathTracer.h kPathLayerNames, same
// order), and where each running sum lives in the accumulator's image array.
#ifndef BL_SHARED_ACCUMULATION_H
#define BL_SHARED_ACCUMULATION_H
#include "Prelude.h"

BL_NAMESPACE_BEGIN

// Radiance by path length in segments: 1 = emitters (and the environment) seen directly, 2 = direct
// light, 3 and 4 = one and two indirect bounces, 5 and more = the rest.
BL_CONST uint kPathEmitted = 0u;
BL_CONST uint kPathDirect = 1u;
BL_CONST uint kPathIndirect1 = 2u;
BL_CONST uint kPathIndirect2 = 3u;
BL_CONST uint kPathRest = 4u;
BL_CONST uint kPathLayerCount = 5u;
BL_CONST uint kAllPathLayers = (1u << kPathLayerCount) - 1u;

// Slots (layers of the rgba32f image array). Every sum is compensated (Neumaier): the slot after
// it holds the running rounding error, so N additions lose ~1 ulp in total instead of ~N ulp/2.
BL_CONST uint kAccumTotalSum = 0u;       // rgb: sum of the sample's radiance; w: samples added
BL_CONST uint kAccumTotalError = 1u;     // rgb: its compensation; w: samples refused as NaN/Inf
BL_CONST uint kAccumSquareSum = 2u;      // rgb: sum of the squared radiance (second moment)
BL_CONST uint kAccumSquareError = 3u;    // rgb: its compensation
BL_CONST uint kAccumFirstLayerSlot = 4u; // then sum and compensation of each layer in `layers`

// Number of slots for a layer mask (bit l = layer l is written).
BL_INLINE uint blAccumSlotCount(uint layers) {
    return kAccumFirstLayerSlot + 2u * uint(bitCount(layers));
}

// Slot of layer l's sum (l must be in `layers`): layers are stored in order, absent ones skipped.
BL_INLINE uint blAccumLayerSlot(uint layers, uint l) {
    return kAccumFirstLayerSlot + 2u * uint(bitCount(layers & ((1u << l) - 1u)));
}

BL_NAMESPACE_END
#endif
