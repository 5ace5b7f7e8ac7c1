// The node side of a pool build, shared by the rasterization (PoolAppend.glsl) and the compute
// (compute_triangles.comp.glsl) backends: the allocator's overflow contract, the exact depth of a
// pixel's ray on a triangle's plane, and linking a node in front of its pixel's list.
#ifndef BL_BUNDLE_POOL_NODES_GLSL
#define BL_BUNDLE_POOL_NODES_GLSL
#include "bundle/BundleBuffers.glsl"

// Fragments that found the pool full: counted in 64 bits (BundleTypes.h: BundleCounters).
void blPoolAddExcess(BundleCounterBlock block, uint count) {
    uint old = atomicAdd(block.counters.excessLow, count);
    if (old + count < old) {
        atomicAdd(block.counters.excessHigh, 1u);
    }
}

// One node index, or kBundleNil when the pool is full (then counted).
uint blPoolAllocateOne(BundleCounterBlock block) {
    if (block.counters.allocated >= block.counters.capacity) {
        blPoolAddExcess(block, 1u);
        return kBundleNil;
    }
    uint index = atomicAdd(block.counters.allocated, 1u);
    return index < block.counters.capacity ? index : kBundleNil;
}

// `count` consecutive node indices from the returned one, or kBundleNil when the pool is full (then
// all are counted). Indices at or past the capacity are fragments that did not fit: they count in
// `allocated` (requested = allocated + excess) and the caller drops them.
uint blPoolAllocate(BundleCounterBlock block, uint count) {
    if (block.counters.allocated >= block.counters.capacity) {
        blPoolAddExcess(block, count);
        return kBundleNil;
    }
    return atomicAdd(block.counters.allocated, count);
}

// Depth along omega where `ray` (a pixel's ray at depth 0) meets the plane (n, offset): false when
// the ray runs inside it (or the plane is degenerate: GpuScene gives such triangles a zero normal).
bool blPoolPlaneDepth(BundleFrame frame, vec3 ray, vec3 n, float offset, out float depth, out bool frontFacesMinusOmega) {
    float cosine = dot(n, frame.direction);
    frontFacesMinusOmega = cosine < 0.0;
    depth = 0.0;
    if (cosine == 0.0) {
        return false;
    }
    depth = (offset - dot(n, ray)) / cosine;
    return abs(depth) < 3.0e38;
}

// Node `index` becomes the head of `pixel`'s list.
void blPoolLink(uvec2 headAddress, uvec2 nodeAddress, uint pixel, uint index, float depth, bool front) {
    uint face = front ? kBundleFrontFaceBit : 0u;
    uint previous = atomicExchange(BundleHeads(headAddress).heads[pixel], index);
    BundleNodes(nodeAddress).nodes[index] = BundleNode(depth, (previous & kBundleIndexMask) | face);
}
#endif
