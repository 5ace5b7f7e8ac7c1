#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, final glossy gather toward the eye ([HHGM10] section 5.3), once per direction after
// its exchange. Per camera pixel (the G-buffer of a jittered camera sample of this direction) whose
// visible point p has a glossy lobe: of the bundle direction's two senses, the one d on the side
// the camera sees (n . d > 0); p is placed in its bundle pixel's sorted list by depth, and the
// nearest fragment beyond it along d (its own surface skipped, Traversal.glsl) is the neighbour
// whose sender radiance arrives at p along d (the environment where the list ends). One direction
// estimates the lobe's reflection toward the eye:
//   L_glossy(p, eye) ~ L_sender(neighbour) f_glossy(p, d, eye) (n . d) / p_r(d),
// summed with the atlas's weights w_j (the shade pass divides by their total). The Lambert part
// of p is the atlas's; the point lights' glossy highlight is the highlight pass's.
#include "modes/atlas/AtlasBuffers.glsl"
#define BL_ACCUM_LAYERS kAtlasAccumLayers
#include "gpu/CameraSet.glsl"
#include "bundle/Traversal.glsl"
#include "shared/Brdf.h"
#include "modes/atlas/GlossyPixel.glsl"

layout(local_size_x = kAtlasViewGroupSize, local_size_y = kAtlasViewGroupSize) in;
layout(push_constant) uniform PushBlock { AtlasGatherPush push; };

vec3 gathered(ivec2 pixel) {
    GpuMaterial m;
    vec3 p, n, eye;
    if (!blAtlasGlossyPixel(pixel, m, p, n, eye) || blBundlePoolOverflowed(BundleCounterBlock(push.pool.counters))) {
        return vec3(0.0);
    }
    BundleFrame frame = blBundlePoolFrame(push.pool, 0u);
    AtlasDirection dir = AtlasDirectionBlock(push.direction).direction;
    float sense = dot(n, frame.direction) >= 0.0 ? 1.0 : -1.0;
    vec3 d = sense * frame.direction;
    vec3 lobe = blEvalBrdf(m, vec3(0.0), n, d, eye) * dot(n, d); // albedo 0: the glossy lobe alone
    if (!any(greaterThan(lobe, vec3(0.0)))) {
        return vec3(0.0);
    }
    vec3 incoming = sense > 0.0 ? dir.environmentForward : dir.environmentBackward;
    ivec2 bundlePixel;
    float depth;
    if (blBundlePixel(frame, p, bundlePixel, depth)) {
        BundleNodes nodes = BundleNodes(push.pool.nodes);
        uint head = blBundleHead(blBundlePoolHeads(push.pool, 0u), frame, bundlePixel);
        float own = blBundleOwnSurfaceEpsilon(frame, dot(n, frame.direction));
        uint neighbour = head == kBundleNil ? kBundleNil : blBundleSortedNearest(nodes, head, depth, sense, own, frame);
        if (neighbour != kBundleNil) {
            uint next = nodes.nodes[neighbour].next;
            uint side = sense > 0.0 ? blAtlasSideFacingBackward(next) : blAtlasSideFacingForward(next);
            BundleHit hit = BundleHitPayload(push.pool.payload).hits[neighbour];
            uint texel = blAtlasHitTexel(hit, push.triangles, push.atlasWidth, push.atlasHeight);
            incoming = AtlasRadiance(push.sender).radiance[kAtlasSides * texel + side].rgb;
        }
    }
    return incoming * lobe * dir.inverseDensity;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) {
        return;
    }
    uint index = uint(pixel.y) * push.width + uint(pixel.x);
    AtlasRadiance sums = AtlasRadiance(push.gathered);
    vec3 sum = push.clear != 0u ? vec3(0.0) : sums.radiance[index].rgb;
    sums.radiance[index] = vec4(sum + push.weight * gathered(pixel), 0.0);
}
