// Body of the benchmark floor's fragment shaders: the same rasterization as a bundle build, but
// each fragment only adds itself to a counter, with the same allocation scheme as the build (one
// atomic per fragment, or per subgroup), so the floor is not slowed by contention the build avoids.
#include "bundle/BundleBuffers.glsl"
#ifdef BL_SUBGROUP_ALLOCATION
#extension GL_KHR_shader_subgroup_ballot : require
#endif

layout(location = 0) in float inDepth;
layout(location = 1) in vec3 inNormal;
layout(push_constant) uniform PushBlock { BundleBuildPush push; };

void main() {
    BundleCounterBlock counter = BundleCounterBlock(push.counterAddress);
#ifdef BL_SUBGROUP_ALLOCATION
    uvec4 live = subgroupBallot(!gl_HelperInvocation);
    if (gl_SubgroupInvocationID == subgroupBallotFindLSB(live)) {
        atomicAdd(counter.counters.requested, subgroupBallotBitCount(live));
    }
#else
    atomicAdd(counter.counters.requested, 1u);
#endif
}
