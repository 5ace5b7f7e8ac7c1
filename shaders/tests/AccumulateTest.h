// Host/device definitions of the accumulator test shader (tests/core/gpu/AccumulatorTest.cpp).
#ifndef BL_TESTS_ACCUMULATE_TEST_H
#define BL_TESTS_ACCUMULATE_TEST_H
#include "../shared/Accumulation.h"

BL_NAMESPACE_BEGIN

// A sparse mask on purpose: layers after an absent one must still find their slots.
BL_CONST uint kAccumTestLayers = (1u << kPathEmitted) | (1u << kPathDirect) | (1u << kPathIndirect2);

BL_CONST uint kAccumTestConstant = 0u; // `value` to the direct layer, every iteration
BL_CONST uint kAccumTestPlain = 1u;    // the same, as a plain float sum (what the test must catch)
BL_CONST uint kAccumTestLayered = 2u;  // 0.25 (l + 1) to every layer l, masked or not
BL_CONST uint kAccumTestUniform = 3u;  // a hashed uniform number in [0, 1) to the direct layer
BL_CONST uint kAccumTestShortfall = 4u; // (x + i) mod 5: 0 NaN, 1 nothing (dropped), else 1

struct AccumTestPush {
    uint kind;
    uint iterations; // samples per pixel, added in one dispatch
    uint width;
    uint height;
    float value;
    uint pad0;
    uint pad1;
    uint pad2;
};
BL_STATIC_ASSERT(sizeof(AccumTestPush) == 32, "AccumTestPush layout");

BL_CONST uint kAccumTestGroupSize = 8u;

BL_NAMESPACE_END
#endif
