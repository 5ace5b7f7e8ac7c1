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
// Split channels (delay_indirect): the neighbour's emission and the environment go to the one-
// bounce sums (weight w_j), its reflected light to the multi-bounce sums (their own weight, once
// indirect light is enabled), as in the atlas.
#include "modes/atlas/AtlasBuffers.glsl"
#define BL_ACCUM_LAYERS kAtlasAccumLayers
#include "gpu/CameraSet.glsl"
#include "bundle/Traversal.glsl"
#include "shared/Brdf.h"
#include "modes/atlas/GlossyPixel.glsl"

layout(local_size_x = kAtlasViewGroupSize, local_size_y = kAtlasViewGroupSize) in;
layout(push_constant) uniform PushBlock { AtlasGatherPush push; };

// The lobe's reflection toward the eye of what the neighbour emits (and the environment) in
// `emitted`, of what it reflects in `reflected`.
void gathered(ivec2 pixel, out vec3 emitted, out vec3 reflected) {
    emitted = vec3(0.0);
    reflected = vec3(0.0);
    GpuMaterial m;
    vec3 p, n, eye;
    if (!blAtlasGlossyPixel(pixel, m, p, n, eye) || blBundlePoolOverflowed(BundleCounterBlock(push.pool.counters))) {
        return;
    }
    BundleFrame frame = blBundlePoolFrame(push.pool, 0u);
    AtlasDirection dir = AtlasDirectionBlock(push.direction).direction;
    float sense = dot(n, frame.direction) >= 0.0 ? 1.0 : -1.0;
    vec3 d = sense * frame.direction;
    vec3 lobe = blEvalBrdf(m, vec3(0.0), n, d, eye) * dot(n, d); // albedo 0: the glossy lobe alone
    if (!any(greaterThan(lobe, vec3(0.0)))) {
        return;
    }
    vec3 incoming = sense > 0.0 ? dir.environmentForward : dir.environmentBackward;
    vec3 incomingReflected = vec3(0.0);
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
            blAtlasSenderParts(dir, kAtlasSides * texel + side, incoming, incomingReflected);
        }
    }
    emitted = incoming * lobe * dir.inverseDensity;
    reflected = incomingReflected * lobe * dir.inverseDensity;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) {
        return;
    }
    uint index = uint(pixel.y) * push.width + uint(pixel.x);
    vec3 emitted, reflected;
    gathered(pixel, emitted, reflected);
    AtlasDirection dir = AtlasDirectionBlock(push.direction).direction;
    AtlasRadiance sums = AtlasRadiance(push.gathered);
    vec3 sum = push.clear != 0u ? vec3(0.0) : sums.radiance[index].rgb;
    if (dir.split == 0u) {
        sums.radiance[index] = vec4(sum + push.weight * (emitted + reflected), 0.0); // one of them is 0
        return;
    }
    sums.radiance[index] = vec4(sum + push.weight * emitted, 0.0);
    if (dir.indirect != 0u) {
        AtlasRadiance indirect = AtlasRadiance(push.gatheredIndirect);
        vec3 sumIndirect = dir.clearIndirect != 0u ? vec3(0.0) : indirect.radiance[index].rgb;
        indirect.radiance[index] = vec4(sumIndirect + dir.weightIndirect * reflected, 0.0);
    }
}
