// Body of the bundle build fragment shaders: append this fragment to its pixel's list. Node
// allocation is one atomic per fragment, or (BL_SUBGROUP_ALLOCATION) one per subgroup: measurably
// faster on lavapipe, where fragments of a quad run in one subgroup.
#include "bundle/BundleBuffers.glsl"
#include "shared/BundleTypes.h"
#include "shared/Octahedral.h"
#ifdef BL_SUBGROUP_ALLOCATION
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_shuffle : require
#endif

layout(location = 0) in float inDepth;
layout(location = 1) in vec3 inNormal;

layout(set = 0, binding = 0) uniform FrameBlock { BundleFrame frame; };
layout(set = 0, binding = 1) readonly buffer MaterialBlock { GpuMaterial materials[]; };

layout(push_constant) uniform PushBlock { BundleBuildPush push; };
#ifdef BL_EXACT_DEPTH
layout(set = 0, binding = 3) readonly buffer PlaneBlock { vec4 planes[]; };

// The exact depth where this pixel's centre ray meets the triangle's plane (what a ray tracer
// computes), and the exact face: no dependence on the rasterizer's sub-pixel snapping. The plane
// is precomputed per triangle in the mesh's space and moved by the rigid model matrix.
bool exactDepth(out float depth, out bool frontFacesMinusOmega) {
    vec4 plane = planes[push.firstTriangle + uint(gl_PrimitiveID)];
    vec3 n = mat3(push.model) * plane.xyz;
    float offset = plane.w + dot(n, push.model[3].xyz);
    float cosine = dot(n, frame.direction);
    vec3 ray = frame.origin + gl_FragCoord.x * frame.pixelSize * frame.axisX +
               gl_FragCoord.y * frame.pixelSize * frame.axisY;
    frontFacesMinusOmega = cosine < 0.0;
    if (cosine == 0.0) {
        return false;
    }
    depth = (offset - dot(n, ray)) / cosine;
    return true;
}
#endif

uint allocateNode(BundleCounterBlock counter) {
#ifdef BL_SUBGROUP_ALLOCATION
    // Helper invocations must not lead: their atomics are discarded.
    uvec4 live = subgroupBallot(!gl_HelperInvocation);
    uint leader = subgroupBallotFindLSB(live);
    uint base = 0u;
    if (gl_SubgroupInvocationID == leader) {
        base = atomicAdd(counter.counters.requested, subgroupBallotBitCount(live));
    }
    base = subgroupShuffle(base, leader);
    return base + subgroupBallotExclusiveBitCount(live);
#else
    return atomicAdd(counter.counters.requested, 1u);
#endif
}

void main() {
    BundleCounterBlock counter = BundleCounterBlock(push.counterAddress);
    uint index = allocateNode(counter);
    if (gl_HelperInvocation || index >= counter.counters.capacity) {
        return; // an overflow is counted (requested > capacity) and the builder rebuilds
    }
    uint pixel = uint(gl_FragCoord.y) * frame.width + uint(gl_FragCoord.x);
    float depth = inDepth;
    bool front = gl_FrontFacing;
#ifdef BL_EXACT_DEPTH
    float exact;
    if (exactDepth(exact, front)) {
        depth = exact;
    }
#endif
    uint face = front ? kBundleFrontFaceBit : 0u;
    uint previous = atomicExchange(BundleHeads(push.headAddress).heads[pixel], index);
    BundleNodes(push.nodeAddress).nodes[index] = BundleNode(depth, (previous & kBundleIndexMask) | face);
    if (push.payloadKind == kBundlePayloadShading) {
        GpuMaterial m = materials[push.material];
        BundleShading s;
        s.normal = blPackOctahedral(normalize(inNormal));
        s.albedo = packUnorm4x8(vec4(m.albedo, blLuminance(m.specular)));
        s.material = push.material;
        BundleShadingPayload(push.payloadAddress).shading[index] = s;
    }
#ifdef BL_EXACT_DEPTH
    // gl_PrimitiveID in a fragment shader needs the geometryShader feature: a separate variant.
    if (push.payloadKind == kBundlePayloadSurface) {
        BundleSurfacePayload(push.payloadAddress).surfaces[index] = BundleSurface(push.firstTriangle + uint(gl_PrimitiveID), 0u);
    }
#endif
}
