#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, after each direction: per texel side, the direction's received radiance joins the
// compensated (Neumaier) weighted sum over directions (weight w_j) and the receiver is cleared.
// Interleaved transfer: the sender becomes emission + direct (point/spot light, direct pass) +
// sum / W, so the next direction already sends what this one brought and direction i carries light
// of up to i bounces. Bounce-by-bounce: the sender stays until the pass's last direction, whose
// update settles the pass's mean and makes it the next pass's sender. The glossy transfer atlas
// (exchange.comp.glsl: what the side's glossy lobe reflects toward the next direction) joins the
// interleaved sender for the next direction only, and is cleared with the receiver.
#include "modes/atlas/AtlasBuffers.glsl"
#include "bundle/BundleBuffers.glsl"

layout(local_size_x = kAtlasGroupSize) in;
layout(push_constant) uniform PushBlock { AtlasUpdatePush push; };

void main() {
    uint slot = gl_GlobalInvocationID.x;
    if (slot >= kAtlasSides * push.texelCount) {
        return;
    }
    uint texel = slot / kAtlasSides;
    uint side = slot % kAtlasSides;
    AtlasReceived received = AtlasReceived(push.received);
    AtlasRadiance sums = AtlasRadiance(push.sums);
    uint base = kAtlasReceivedWords * slot;
    precise vec3 x = push.weight * vec3(uintBitsToFloat(received.words[base]), uintBitsToFloat(received.words[base + 1u]),
                                        uintBitsToFloat(received.words[base + 2u]));
    uint g = base + kAtlasReceivedGlossy;
    vec3 glossy = vec3(uintBitsToFloat(received.words[g]), uintBitsToFloat(received.words[g + 1u]),
                       uintBitsToFloat(received.words[g + 2u]));
    for (uint w = 0u; w < kAtlasReceivedWords; ++w) {
        received.words[base + w] = 0u;
    }
    precise vec3 sum = push.clearSums != 0u ? vec3(0.0) : sums.radiance[2u * slot].rgb;
    precise vec3 error = push.clearSums != 0u ? vec3(0.0) : sums.radiance[2u * slot + 1u].rgb;
    precise vec3 t = sum + x;
    bvec3 sumBigger = greaterThanEqual(abs(sum), abs(x));
    precise vec3 lost = mix((x - t) + sum, (sum - t) + x, sumBigger);
    error += lost;
    vec3 mean = (t + error) * push.inverseTotalWeight;
    AtlasRadiance sender = AtlasRadiance(push.sender);
    vec3 direct = AtlasRadiance(push.direct).radiance[slot].rgb;
    if (push.transfer == kAtlasTransferInterleaved) {
        sums.radiance[2u * slot] = vec4(t, 0.0);
        sums.radiance[2u * slot + 1u] = vec4(error, 0.0);
        vec3 emitted = side == kAtlasFront ? AtlasTexels(push.texels).texels[texel].emission : vec3(0.0);
        sender.radiance[slot] = vec4(emitted + direct + mean + glossy, 0.0);
    } else if (push.settle != 0u) {
        // Bounce: the pass ends; its mean settles and is what the next pass sends (pure: the
        // emission went in pass 1 only).
        AtlasRadiance settled = AtlasRadiance(push.settled);
        settled.radiance[slot] = vec4(settled.radiance[slot].rgb + mean, 0.0);
        sender.radiance[slot] = vec4(mean + (push.directIntoSender != 0u ? direct : vec3(0.0)), 0.0);
        sums.radiance[2u * slot] = vec4(0.0);
        sums.radiance[2u * slot + 1u] = vec4(0.0);
    } else {
        sums.radiance[2u * slot] = vec4(t, 0.0);
        sums.radiance[2u * slot + 1u] = vec4(error, 0.0);
    }
}
