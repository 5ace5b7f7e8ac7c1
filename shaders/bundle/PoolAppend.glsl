// Body of the pool build fragment shaders: append this fragment to its pixel's list in the
// slot's head slice. Variants (defines before the include):
//   BL_SPLATS               geometry is point splats (pool_splats.vert): cut to the disc, exact
//                           depth on the splat's plane, payload id = point index
//   BL_EXACT_DEPTH          triangles with gl_PrimitiveID (the geometryShader feature): depth and
//                           face from the exact ray-plane hit; the hit payload needs it
//   BL_SUBGROUP_ALLOCATION  one atomic per subgroup instead of one per fragment
//   BL_COUNT_ONLY           the benchmark floor: allocate (count) and store nothing
// A fragment that finds the pool full is counted, never stored (BundleTypes.h: BundleCounters).
#include "bundle/BundleBuffers.glsl"
#include "bundle/PoolNodes.glsl"
#include "bundle/Projection.glsl"
#include "shared/GpuTypes.h"
#include "shared/Octahedral.h"
#include "bundle/PoolHit.glsl"
#ifdef BL_SUBGROUP_ALLOCATION
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_shuffle : require
#endif

layout(location = 0) in float inDepth;
layout(location = 1) in vec3 inNormal;
#ifdef BL_SPLATS
layout(location = 2) in vec2 inDisc;
layout(location = 3) flat in uint inSplat;
#endif

layout(push_constant) uniform PushBlock { BundleDrawPush push; };
// The pool's payload kind is fixed for its pipelines' life (BundlePool): as a constant, the hit
// payload's code leaves visibility-only builds, which lavapipe would otherwise run under a mask.
layout(constant_id = kBundleSpecHitPayload) const bool kHitPayload = true;

#ifdef BL_EXACT_DEPTH
layout(set = 0, binding = 0) readonly buffer PlaneBlock { vec4 planes[]; };
layout(set = 0, binding = 1) readonly buffer VertexBlock { GpuVertex vertices[]; };
layout(set = 0, binding = 2) readonly buffer IndexBlock { uint indices[]; };
#endif

// A node index for each live invocation, or kBundleNil when the pool is full (then counted).
uint allocateNode(BundleCounterBlock block, bool live) {
#ifdef BL_SUBGROUP_ALLOCATION
    // Helper and discarded invocations must not lead: their atomics would be lost or wrong.
    uvec4 ballot = subgroupBallot(live);
    uint count = subgroupBallotBitCount(ballot);
    if (count == 0u) {
        return kBundleNil;
    }
    uint leader = subgroupBallotFindLSB(ballot);
    uint base = kBundleNil;
    if (gl_SubgroupInvocationID == leader) {
        if (block.counters.allocated < block.counters.capacity) {
            base = atomicAdd(block.counters.allocated, count);
        } else {
            blPoolAddExcess(block, count);
        }
    }
    base = subgroupShuffle(base, leader);
    if (!live || base == kBundleNil) {
        return kBundleNil;
    }
    uint index = base + subgroupBallotExclusiveBitCount(ballot);
    return index < block.counters.capacity ? index : kBundleNil;
#else
    return live ? blPoolAllocateOne(block) : kBundleNil;
#endif
}

// The pixel centre's ray (at depth 0) in world space.
vec3 pixelRay(BundleFrame frame) { return blBundlePixelRay(frame, gl_FragCoord.xy); }

bool planeDepth(BundleFrame frame, vec3 n, float offset, out float depth, out bool frontFacesMinusOmega) {
    return blPoolPlaneDepth(frame, pixelRay(frame), n, offset, depth, frontFacesMinusOmega);
}

void main() {
    BundleFrame frame = BundleFrames(push.frameAddress).frames[0];
    BundleCounterBlock block = BundleCounterBlock(push.counterAddress);
    bool live = !gl_HelperInvocation;
#ifdef BL_SPLATS
    live = live && dot(inDisc, inDisc) <= 1.0; // cut the circumscribing triangle to the disc
#endif
    uint index = allocateNode(block, live);
#ifdef BL_COUNT_ONLY
    return;
#else
    if (index == kBundleNil) {
        return;
    }
    uint pixel = uint(gl_FragCoord.y) * frame.width + uint(gl_FragCoord.x);
    float depth = inDepth;
    bool front = gl_FrontFacing;
    vec3 planeNormal = -frame.direction;
#if defined(BL_SPLATS)
    BundleSplat splat = BundleSplats(push.splatAddress).splats[inSplat];
    planeNormal = splat.normal;
    float exact;
    if (planeDepth(frame, splat.normal, dot(splat.normal, splat.position), exact, front)) {
        depth = exact;
    }
#elif defined(BL_EXACT_DEPTH)
    uint triangle = push.firstPrimitive + uint(gl_PrimitiveID);
    vec4 plane = planes[triangle];
    vec3 n = mat3(push.model) * plane.xyz;
    float exact;
    if (planeDepth(frame, n, plane.w + dot(n, push.model[3].xyz), exact, front)) {
        depth = exact;
    }
    if (dot(n, n) > 0.0) {
        planeNormal = n;
    }
#endif
    blPoolLink(push.headAddress, push.nodeAddress, pixel, index, depth, front);
#if defined(BL_SPLATS) || defined(BL_EXACT_DEPTH)
    if (kHitPayload) {
        BundleHit hit;
#ifdef BL_SPLATS
        hit.normal = blPackOctahedral(planeNormal);
        hit.plane = hit.normal;
        hit.material = (splat.material & kBundleHitMaterialMask) | kBundleHitSplat;
        hit.uv = vec2(0.0);
        hit.id = inSplat;
        hit.barycentric = 0u;
        hit.pad = 0u;
#else
        uint first = 3u * triangle;
        BlPoolTriangle corners = blPoolTriangle(vertices[indices[first] + push.vertexOffset],
                                                vertices[indices[first + 1u] + push.vertexOffset],
                                                vertices[indices[first + 2u] + push.vertexOffset], push.model,
                                                planeNormal, -frame.direction, push.material, triangle);
        hit = blPoolTriangleHit(corners, pixelRay(frame) + depth * frame.direction);
#endif
        BundleHitPayload(push.payloadAddress).hits[index] = hit;
    }
#endif
#endif
}
