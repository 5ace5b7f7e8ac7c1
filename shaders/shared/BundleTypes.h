// Global ray-bundles (EQUATIONS.md section 1): per-pixel linked lists of every surface crossing
// along parallel rays. Defined once for the host and the shaders.
//
// A bundle's frame is an orthographic camera looking along `direction`: pixel (i, j)'s ray is
//   origin + (i + 0.5) pixelSize axisX + (j + 0.5) pixelSize axisY + t direction,
// and a fragment's depth is t, in world units (float: the same relative precision at any scale).
//
// Nodes are stored as structure-of-arrays: the core (depth, next + face) that traversal needs, and
// an optional payload array the mode chooses (shading attributes, or the surface id), indexed by
// the same node index.
#ifndef BL_SHARED_BUNDLE_TYPES_H
#define BL_SHARED_BUNDLE_TYPES_H
#include "Prelude.h"

BL_NAMESPACE_BEGIN

BL_CONST uint kBundleNil = 0x7fffffffu;       // end of a list (in the low 31 bits of `next`)
BL_CONST uint kBundleIndexMask = 0x7fffffffu; // node index bits of `next`
BL_CONST uint kBundleFrontFaceBit = 0x80000000u; // set: the triangle's front faces -direction

struct BundleFrame {
    vec3 origin;     // corner of pixel (0, 0) at depth 0
    float pixelSize; // world units
    vec3 axisX;
    uint width;
    vec3 axisY;
    uint height;
    vec3 direction;  // unit: the bundle direction omega
    float depthNear; // depth range of the scene: depths are mapped to [0, 1] over it for clipping
    float depthFar;
    float depthEpsilon; // world units: fragments closer than this to a point's depth are the point's own
    uint pad0;
    uint pad1;
};
BL_STATIC_ASSERT(sizeof(BundleFrame) == 80, "BundleFrame layout");

struct BundleNode {
    float depth;
    uint next; // index of the next node, kBundleNil at the end; kBundleFrontFaceBit = face
};
BL_STATIC_ASSERT(sizeof(BundleNode) == 8, "BundleNode layout");

// Payload "shading" ([TO12s]'s compact node without depth/next): 12 bytes.
struct BundleShading {
    uint normal;      // octahedral, 2 x 16-bit snorm, facing the side the face bit says
    uint albedo;      // rgba8 unorm: albedo rgb, a = specular luminance
    uint material;    // material index
};
BL_STATIC_ASSERT(sizeof(BundleShading) == 12, "BundleShading layout");

// Payload "surface": which triangle, and where on it (for multibounce / atlas lookups).
struct BundleSurface {
    uint triangle;    // global triangle index (GpuScene order)
    uint barycentric; // 2 x 16-bit unorm (b1, b2)
};
BL_STATIC_ASSERT(sizeof(BundleSurface) == 8, "BundleSurface layout");

BL_CONST uint kBundlePayloadNone = 0u;
BL_CONST uint kBundlePayloadShading = 1u;
BL_CONST uint kBundlePayloadSurface = 2u;

// Written by the build pass: nodes asked for (may exceed capacity: then the build overflowed and
// nothing past capacity was stored).
struct BundleCounters {
    uint requested;
    uint capacity;
    uint pad0;
    uint pad1;
};
BL_STATIC_ASSERT(sizeof(BundleCounters) == 16, "BundleCounters layout");

// Push constants of the build pass: the frame, the model matrix, buffer addresses (uvec2: no
// 64-bit integers needed), and a tile to restrict the build to.
struct BundleBuildPush {
    mat4 model;
    uvec2 headAddress;
    uvec2 nodeAddress;
    uvec2 payloadAddress;
    uvec2 counterAddress;
    uint payloadKind;
    uint material;
    uint firstTriangle; // global index of the draw's first triangle
    uint vertexOffset;  // the draw's vertex offset (exact depths fetch the triangle)
};
BL_STATIC_ASSERT(sizeof(BundleBuildPush) == 112, "BundleBuildPush layout");

BL_NAMESPACE_END
#endif
