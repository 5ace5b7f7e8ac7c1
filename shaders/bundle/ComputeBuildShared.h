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
    mat4 model;           // the mesh's rigid transform at the bundle's time
    uvec2 frameAddress;
    uvec2 headAddress;
    uvec2 nodeAddress;
    uvec2 counterAddress;
    uint firstPrimitive;  // global index of the draw's first triangle
    uint vertexOffset;
    uint triangleCount;   // of this draw
    uint rowsPerBand;     // tile rows one invocation walks (dispatch y: the bands)
};
BL_STATIC_ASSERT(sizeof(BundleComputePush) == 112, "BundleComputePush layout");

BL_CONST uint kBundleComputeGroupSize = 64u;
// Most pixels one invocation walks (rowsPerBand = max(1, this / tile width)).
BL_CONST uint kBundleComputeBandPixels = 32768u;

BL_NAMESPACE_END
#endif
