// Buffer references to a bundle pool's storage (device addresses: one binding is not limited to
// lavapipe's 128 MiB, and the pool can be reallocated without new descriptors).
#ifndef BL_BUNDLE_BUFFERS_GLSL
#define BL_BUNDLE_BUFFERS_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "shared/BundleTypes.h"

layout(buffer_reference, std430, buffer_reference_align = 4) buffer BundleHeads { uint heads[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer BundleNodes { BundleNode nodes[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer BundleHitPayload { BundleHit hits[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer BundlePrevious { uint previous[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer BundleFrames { BundleFrame frames[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer BundleSplats { BundleSplat splats[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer BundleCounterBlock { BundleCounters counters; };

// True when a build into the pool ran out of nodes: some lists lack fragments, so every consumer
// skips its work and the mode redoes the iteration with a larger pool.
bool blBundlePoolOverflowed(BundleCounterBlock block) {
    BundleCounters c = block.counters;
    return c.excessLow != 0u || c.excessHigh != 0u || c.allocated > c.capacity;
}

// base + count * stride as a 64-bit address in two words (no 64-bit integer types needed).
uvec2 blAddressOffset(uvec2 base, uint count, uint stride) {
    uint high, low;
    umulExtended(count, stride, high, low);
    uint carry;
    uint sumLow = uaddCarry(base.x, low, carry);
    return uvec2(sumLow, base.y + high + carry);
}

// Slot s's frame and heads in a pool.
BundleFrame blBundlePoolFrame(BundlePoolView pool, uint slot) { return BundleFrames(pool.frames).frames[slot]; }
BundleHeads blBundlePoolHeads(BundlePoolView pool, uint slot) {
    return BundleHeads(blAddressOffset(pool.heads, slot * pool.slotPixels, 4u));
}

#endif
