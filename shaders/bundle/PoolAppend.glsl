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
#include "shared/Barycentrics.h"
#include "shared/Octahedral.h"
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

// A unit vector along v, or `fallback` when v cancelled to (nearly) zero: normalize(0) is NaN.
vec3 safeNormalize(vec3 v, vec3 fallback) {
    float lengthSquared = dot(v, v);
    return lengthSquared > 1e-30 ? v * inversesqrt(lengthSquared) : fallback;
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
        // Barycentrics of the ray's hit point, from the triangle's corners in world space.
        uint first = 3u * triangle;
        GpuVertex v0 = vertices[indices[first] + push.vertexOffset];
        GpuVertex v1 = vertices[indices[first + 1u] + push.vertexOffset];
        GpuVertex v2 = vertices[indices[first + 2u] + push.vertexOffset];
        vec3 p0 = (push.model * vec4(v0.positionU.xyz, 1.0)).xyz;
        vec3 e1 = mat3(push.model) * (v1.positionU.xyz - v0.positionU.xyz);
        vec3 e2 = mat3(push.model) * (v2.positionU.xyz - v0.positionU.xyz);
        vec2 b = blTriangleBarycentrics(pixelRay(frame) + depth * frame.direction - p0, e1, e2);
        float b0 = 1.0 - b.x - b.y;
        vec3 shading = b0 * v0.normalV.xyz + b.x * v1.normalV.xyz + b.y * v2.normalV.xyz;
        vec3 facet = safeNormalize(planeNormal, -frame.direction);
        hit.normal = blPackOctahedral(safeNormalize(mat3(push.model) * shading, facet));
        hit.plane = blPackOctahedral(facet);
        hit.material = push.material & kBundleHitMaterialMask;
        hit.uv = b0 * vec2(v0.positionU.w, v0.normalV.w) + b.x * vec2(v1.positionU.w, v1.normalV.w) +
                 b.y * vec2(v2.positionU.w, v2.normalV.w);
        hit.id = triangle;
        hit.barycentric = packUnorm2x16(b);
        hit.pad = 0u;
#endif
        BundleHitPayload(push.payloadAddress).hits[index] = hit;
    }
#endif
#endif
}
