// Global ray-bundles ([RB 1], papers/EQUATIONS.md): per-pixel linked lists of every surface crossing
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
    // Tiles: a tile keeps its frame's origin and grid and adds the integer offset of its first
    // pixel, so it projects and rasterizes every point exactly as the whole frame does
    // (shaders/bundle/Projection.glsl). A whole frame: offset 0, grid = width x height.
    uint tileX;
    uint tileY;
    uint gridWidth; // pixels of the whole frame
    uint gridHeight;
    uint pad0;
    uint pad1;
};
BL_STATIC_ASSERT(sizeof(BundleFrame) == 96, "BundleFrame layout");

struct BundleNode {
    float depth;
    uint next; // index of the next node, kBundleNil at the end; kBundleFrontFaceBit = face
};
BL_STATIC_ASSERT(sizeof(BundleNode) == 8, "BundleNode layout");

// Payload "hit": what a consumer needs to shade a fragment without going back to the scene.
// Written by the exact rasterized build and the compute build (both know the triangle:
// bundle/PoolHit.glsl), 32 bytes per node beside the core.
struct BundleHit {
    uint normal;      // octahedral (2 x 16-bit snorm) shading normal in world space, as interpolated
                      // (not turned to any side: compare with the face bit or the query direction)
    uint material;    // material index in the low 24 bits, kBundleHit* flags in the high 8
    vec2 uv;          // material texture coordinates at the pixel's ray (float: tiled UVs stay exact)
    uint id;          // global triangle index (GpuScene order), or the point index of a splat
    uint barycentric; // 2 x 16-bit unorm (b1, b2) of the ray's hit in the triangle; 0 for splats
    uint plane;       // octahedral normal of the fragment's facet (a splat's plane): where the walks
                      // place it (bundle/Traversal.glsl). A smooth mesh's shading normal is not its
                      // facet's plane: placed by it, a bowl's neighbouring facets rose in front of
                      // the point leaving them, and multibounce's first bounce inside a bowl read
                      // 0.74 of the reference (0.98 by the facets' planes).
    uint pad;
};
BL_STATIC_ASSERT(sizeof(BundleHit) == 32, "BundleHit layout");

BL_CONST uint kBundleHitMaterialMask = 0x00ffffffu;
BL_CONST uint kBundleHitSplat = 0x01000000u; // the fragment is a point splat: `id` is a point index

BL_CONST uint kBundlePayloadNone = 0u;
BL_CONST uint kBundlePayloadHit = 1u;
// Specialization constant of the build's fragment shaders (bundle/PoolAppend.glsl): 1 where the
// pool stores the hit payload.
BL_CONST uint kBundleSpecHitPayload = 0u;
BL_CONST uint kBundleSpecCount = 1u;

// Geometry kinds a bundle is built from.
BL_CONST uint kBundleGeometryTriangles = 0u;
BL_CONST uint kBundleGeometrySplats = 1u;

// A point splat for imperfect bundles ([TO12p]): a disc of `radius` about `position` in the plane
// of `normal`, rasterized as the tangent-space triangle circumscribing it and cut to the circle
// (fragments outside are discarded before a node is allocated).
struct BundleSplat {
    vec3 position;
    float radius;   // world units, > 0
    vec3 normal;    // unit
    uint material;
};
BL_STATIC_ASSERT(sizeof(BundleSplat) == 32, "BundleSplat layout");
// |n.n - 1| beyond which a splat's normal is refused (the splat is not drawn): far above the
// rounding of a normalized float vector, far below a forgotten normalization.
BL_CONST float kBundleSplatNormalTolerance = 1e-3f;

// The node allocator of a pool, shared by every bundle built into it. A fragment that finds the
// pool full adds itself to `excess` (a 64-bit count in two words, low word carrying into the high
// one) instead of `allocated`, so the total asked for, allocated + excess, is exact however far it
// passes 2^32, while `allocated` stays below capacity + the fragments in flight. Consumers test
// blBundlePoolOverflowed() and skip their work: the mode grows the pool and redoes the iteration.
struct BundleCounters {
    uint allocated;  // nodes handed out (indices >= capacity were not stored)
    uint capacity;   // nodes the pool holds
    uint excessLow;  // fragments that found the pool full, low 32 bits
    uint excessHigh; // high 32 bits
};
BL_STATIC_ASSERT(sizeof(BundleCounters) == 16, "BundleCounters layout");

// Push constants of one draw of a pool build: where the bundle goes (its frame, its slot's heads)
// and what is drawn (a mesh's triangles with its model matrix, or a range of splats). 128 bytes,
// the push-constant size every device guarantees.
struct BundleDrawPush {
    mat4 model;           // triangles: the mesh's rigid transform at the bundle's time
    uvec2 frameAddress;   // this slot's BundleFrame
    uvec2 headAddress;    // this slot's heads
    uvec2 nodeAddress;
    uvec2 payloadAddress; // 0 without payload
    uvec2 counterAddress;
    uvec2 splatAddress;   // splats: the BundleSplat array
    uint unused0;         // (the payload kind is the pipelines' kBundleSpecHitPayload)
    uint material;        // triangles: the mesh's material
    uint firstPrimitive;  // global index of the draw's first triangle, or its first splat
    uint vertexOffset;    // triangles: the draw's vertex offset (exact variants fetch the triangle)
};
BL_STATIC_ASSERT(sizeof(BundleDrawPush) == 128, "BundleDrawPush layout");

// Everything a consumer shader needs to read the bundles of a pool: buffer addresses, and the
// layout of the head slices (slot s's heads start at s * slotPixels).
struct BundlePoolView {
    uvec2 heads;
    uvec2 nodes;
    uvec2 payload;   // 0 without payload
    uvec2 frames;    // BundleFrame per slot
    uvec2 counters;
    uvec2 previous;  // after sorting: per node, the node before it in its list (kBundleNil first)
    uint slotPixels; // head entries per slot
    uint slots;
    uint payloadKind;
    uint sorted;     // 1 when the lists were ordered by the sort pass since their build
};
BL_STATIC_ASSERT(sizeof(BundlePoolView) == 64, "BundlePoolView layout");

// Push constants of the pool's compute passes (sort, statistics).
struct BundlePoolPush {
    BundlePoolView pool;
    uint slot;
    uint pad0;
    uvec2 statsAddress; // statistics pass: BundleListStats
};
BL_STATIC_ASSERT(sizeof(BundlePoolPush) == 80, "BundlePoolPush layout");

// What the statistics pass finds by walking every list of a slot once.
struct BundleListStats {
    uint nonEmptyPixels;
    uint longestList;
    uint reachableNodes; // nodes reached from the heads: equals the stored nodes when nothing is lost
    uint pad0;
};
BL_STATIC_ASSERT(sizeof(BundleListStats) == 16, "BundleListStats layout");

// How far along the ray a point's own surface can appear in its bundle pixel: the pixel centre's
// ray meets the point's plane up to one pixel away, i.e. up to pixelSize * tan(incidence) deeper or
// shallower. 1 px * tan covers it with margin; capped, since beyond ~85 degrees the cosine weight of
// any estimator makes the term negligible anyway.
BL_CONST float kBundleOwnSurfacePixels = 1.0f;
// Build vertices are snapped to 1/kBundleSubpixelGrid of a pixel in the frame's whole grid
// (Projection.glsl): the subpixel precision of the rasterizers we know (8 bits), so the snap moves
// nothing they would not, and tiles rasterize exactly as the whole frame.
BL_CONST float kBundleSubpixelGrid = 256.0f;
BL_CONST float kBundleMaxOwnSurfaceTangent = 12.0f;

// Nodes a pixel's list can hold in the sort pass's local array; longer lists are sorted in place
// (insertion into the linked list: slower, equally exact).
BL_CONST uint kBundleSortLocalNodes = 64u;
BL_CONST uint kBundleSortGroupSize = 64u;

// Push constants of the depth-map pass (a directional shadow map along omega; its frame is a
// uniform written in the command stream).
struct BundleDepthMapPush {
    mat4 model;
};
BL_STATIC_ASSERT(sizeof(BundleDepthMapPush) == 64, "BundleDepthMapPush layout");

BL_NAMESPACE_END
#endif
