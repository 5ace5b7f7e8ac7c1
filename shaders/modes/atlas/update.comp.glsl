#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, after each direction: per texel side that this direction changed (the touched list
// the exchange and the glossy lights pass appended to), the direction's received radiance joins
// the compensated (Neumaier) weighted sum over directions (weight w_j) and the receiver is cleared;
// the glossy transfer atlas (exchange.comp.glsl: what the side's glossy lobe reflects toward the
// next direction) is kept, tagged with this direction, for the next direction only. A side not on
// the list received nothing: its sums stand. Interleaved transfer stores the sender in parts
// (AtlasSenderRecord: emission + direct, the sum, the tagged glossy transfer; written whole once
// before the first direction by this pass's init mode), formed as base + sum / W + glossy where
// it is read (AtlasBuffers.glsl: blAtlasSender), so direction i + 1 already sends what direction
// i brought and direction i carries light of up to i bounces.
// Bounce-by-bounce: the sender stays until the pass's last direction, whose update (over every
// texel side) settles the pass's mean and makes it the next pass's sender.
// Split channels (delay_indirect): the multi-bounce channel's received words join its own sums
// with its own weight.
#include "modes/atlas/AtlasBuffers.glsl"
#include "bundle/BundleBuffers.glsl"

layout(local_size_x = kAtlasGroupSize) in;
layout(push_constant) uniform PushBlock { AtlasUpdatePush push; };

// sums[2 slot] (sum) and sums[2 slot + 1] (compensation) += x, Neumaier's step; the new sum and
// compensation are written unless `write` is false, and returned.
void addCompensated(AtlasRadiance sums, uint slot, vec3 x, bool clear, bool write, out vec3 sumOut, out vec3 errorOut) {
    precise vec3 sum = clear ? vec3(0.0) : sums.radiance[2u * slot].rgb;
    precise vec3 error = clear ? vec3(0.0) : sums.radiance[2u * slot + 1u].rgb;
    precise vec3 t = sum + x;
    bvec3 sumBigger = greaterThanEqual(abs(sum), abs(x));
    precise vec3 lost = mix((x - t) + sum, (sum - t) + x, sumBigger);
    error += lost;
    if (write) {
        sums.radiance[2u * slot] = vec4(t, 0.0);
        sums.radiance[2u * slot + 1u] = vec4(error, 0.0);
    }
    sumOut = t;
    errorOut = error;
}

void main() {
    uint slot = gl_GlobalInvocationID.x;
    if (push.mode == kAtlasUpdateListed) {
        AtlasTouched list = AtlasTouched(push.touched);
        if (slot >= list.words[0]) {
            return;
        }
        slot = list.words[kAtlasTouchedHeader + slot];
    } else if (slot >= kAtlasSides * push.texelCount) {
        return;
    }
    AtlasSenders senders = AtlasSenders(push.senders);
    if (push.mode == kAtlasUpdateInit) {
        // The constant part of the sender: emission (front; the split one-bounce channel takes it
        // from the texel) + point/spot light of the direct pass.
        bool emits = slot % kAtlasSides == kAtlasFront && push.receivedIndirect == uvec2(0u);
        vec3 emitted = emits ? AtlasTexels(push.texels).texels[slot / kAtlasSides].emission : vec3(0.0);
        vec3 direct = AtlasRadiance(push.direct).radiance[slot].rgb;
        senders.records[slot] = AtlasSenderRecord(emitted + direct, ~0u, vec3(0.0), 0u, vec3(0.0), 0u);
        return;
    }
    AtlasReceived received = AtlasReceived(push.received);
    AtlasRadiance sums = AtlasRadiance(push.sums);
    uint base = kAtlasReceivedWords * slot;
    precise vec3 x = push.weight * vec3(uintBitsToFloat(received.words[base]), uintBitsToFloat(received.words[base + 1u]),
                                        uintBitsToFloat(received.words[base + 2u]));
    uint g = base + kAtlasReceivedGlossy;
    uvec3 glossy = uvec3(received.words[g], received.words[g + 1u], received.words[g + 2u]);
    for (uint w = 0u; w < kAtlasReceivedWords; ++w) {
        received.words[base + w] = 0u;
    }
    bool clear = push.clearSums != 0u;
    bool settling = push.transfer == kAtlasTransferBounce && push.settle != 0u;
    vec3 t, error;
    addCompensated(sums, slot, x, clear, !settling, t, error);
    if (push.receivedIndirect != uvec2(0u)) {
        AtlasReceived indirect = AtlasReceived(push.receivedIndirect);
        vec3 y = push.weightIndirect * vec3(uintBitsToFloat(indirect.words[4u * slot]),
                                            uintBitsToFloat(indirect.words[4u * slot + 1u]),
                                            uintBitsToFloat(indirect.words[4u * slot + 2u]));
        for (uint w = 0u; w < 4u; ++w) {
            indirect.words[4u * slot + w] = 0u;
        }
        if (push.weightIndirect > 0.0) {
            vec3 ti, ei;
            addCompensated(AtlasRadiance(push.sumsIndirect), slot, y, false, true, ti, ei);
        }
    }
    if (push.transfer == kAtlasTransferInterleaved) {
        precise vec3 sum = t + error;
        senders.records[slot].sum = sum;
        senders.records[slot].glossy = uintBitsToFloat(glossy);
        senders.records[slot].tag = push.iteration;
    } else if (settling) {
        // Bounce: the pass ends; its mean settles and is what the next pass sends (pure: the
        // emission went in pass 1 only).
        vec3 mean = (t + error) * push.inverseTotalWeight;
        vec3 direct = AtlasRadiance(push.direct).radiance[slot].rgb;
        AtlasRadiance settled = AtlasRadiance(push.settled);
        settled.radiance[slot] = vec4(settled.radiance[slot].rgb + mean, 0.0);
        AtlasRadiance(push.sender).radiance[slot] = vec4(mean + (push.directIntoSender != 0u ? direct : vec3(0.0)), 0.0);
        sums.radiance[2u * slot] = vec4(0.0);
        sums.radiance[2u * slot + 1u] = vec4(0.0);
    }
}
