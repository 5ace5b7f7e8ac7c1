// Host/device definitions of the compute bundle builder (core/bundle/ComputeBundleRasterizer.h).
#ifndef BL_BUNDLE_COMPUTE_BUILD_SHARED_H
#define BL_BUNDLE_COMPUTE_BUILD_SHARED_H
#include "../shared/BundleTypes.h"

BL_NAMESPACE_BEGIN

// The clear pass: the slot's frame written, its heads emptied.
struct BundleComputeClearPush {
    BundleFrame frame;
    uvec2 frameAddress; // the slot's BundleFrame
    uvec2 headAddress;  // the slot's heads
    uint pixels;        // frame.width * frame.height
    uint pad0;
    uint pad1;
    uint pad2;
};
BL_STATIC_ASSERT(sizeof(BundleComputeClearPush) == 128, "BundleComputeClearPush layout");

// The triangles pass: one invocation per triangle of one draw.
struct BundleComputePush {
    mat3x4 modelRows;     // the mesh's rigid transform at the bundle's time, as its three rows (the
                          // fourth is 0 0 0 1): 16 bytes that the hit payload's address needs
    uvec2 frameAddress;
    uvec2 headAddress;
    uvec2 nodeAddress;
    uvec2 counterAddress;
    uvec2 payloadAddress; // BundleHit per node, or 0 for visibility bundles
    uint firstPrimitive;  // global index of the draw's first triangle
    uint vertexOffset;
    uint triangleCount;   // of this draw
    uint rowsPerBand;     // tile rows one invocation of the big pass walks
    uvec2 bigAddress;     // BundleComputeBig: the draw's triangles too large for one invocation
    uint pass;            // kBundleComputeSmallPass or kBundleComputeBigPass
    uint bands;           // tile rows / rowsPerBand, rounded up
    uint material;        // the mesh's material (hit payload)
    uint pad0;
};
BL_STATIC_ASSERT(sizeof(BundleComputePush) == 128, "BundleComputePush layout");

// Triangles whose box holds more than kBundleComputeBandPixels pixels, listed by the small pass;
// `dispatch` is the big pass's indirect dispatch (x: bands in groups, y: listed triangles).
struct BundleComputeBigHeader {
    uint dispatchX;
    uint dispatchY;
    uint dispatchZ;
    uint pad0;
};
BL_STATIC_ASSERT(sizeof(BundleComputeBigHeader) == 16, "BundleComputeBigHeader layout");

// Small pass: one invocation per triangle walks its whole box, or lists it as big. Big pass:
// invocation (band, i) walks listed triangle i's rows in that band.
BL_CONST uint kBundleComputeSmallPass = 0u;
BL_CONST uint kBundleComputeBigPass = 1u;

BL_CONST uint kBundleComputeGroupSize = 64u;
// Most pixels one invocation walks (rowsPerBand = max(1, this / tile width); lavapipe ends a loop
// after 65535 iterations).
BL_CONST uint kBundleComputeBandPixels = 32768u;

BL_NAMESPACE_END
#endif
