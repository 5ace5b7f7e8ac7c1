#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// Runs the shadow cubes' lookup (gpu/ShadowCubeLookup.glsl, blShadowFilter) on points a test places:
// per query (point x, normal n) the visibility of cube 0's centre `light` from x's side n as float
// bits, or 0xffffffff where n faces the light at a cosine below `minCosine` (every caller asks only
// where n faces the light). centreOnly: the filter without
// the crease rule (what the test's mutation check runs).
#define BL_SHADOW_SET 0
#define BL_SHADOW_BINDING 0
#include "gpu/ShadowCubeLookup.glsl"

layout(local_size_x = 64) in;

#include "tests/BoxQueries.glsl"

layout(push_constant) uniform PushBlock {
    BoxQueryPush box;
    uint resolution;
    uint taps;
    vec3 light;
    float minCosine;
} push;

void main() {
    vec3 x, n;
    if (!blBoxQuery(push.box, x, n)) {
        return;
    }
    vec3 p = x - push.light;
    uint result = 0xffffffffu;
    if (-dot(n, normalize(p)) >= push.minCosine) {
        result = floatBitsToUint(blShadowFilter(0u, 0u, push.resolution, p, n, int(push.taps), push.box.centreOnly == 0u));
    }
    BoxAnswers(push.box.results).answers[gl_GlobalInvocationID.x] = result;
}
