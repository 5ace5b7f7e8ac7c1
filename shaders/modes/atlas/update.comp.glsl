#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, after each direction: per texel side, the direction's received radiance joins the
// compensated (Neumaier) weighted sum over directions (weight w_j), the sender becomes
// emission + direct (point/spot light, direct pass) + sum / W (interleaved transfer: the next direction already sends what this one
// brought, so direction i carries light of up to i bounces), and the receiver is cleared.
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
    precise vec3 x = push.weight * vec3(uintBitsToFloat(received.words[4u * slot]), uintBitsToFloat(received.words[4u * slot + 1u]),
                          uintBitsToFloat(received.words[4u * slot + 2u]));
    received.words[4u * slot] = 0u;
    received.words[4u * slot + 1u] = 0u;
    received.words[4u * slot + 2u] = 0u;
    precise vec3 sum = push.clearSums != 0u ? vec3(0.0) : sums.radiance[2u * slot].rgb;
    precise vec3 error = push.clearSums != 0u ? vec3(0.0) : sums.radiance[2u * slot + 1u].rgb;
    precise vec3 t = sum + x;
    bvec3 sumBigger = greaterThanEqual(abs(sum), abs(x));
    precise vec3 lost = mix((x - t) + sum, (sum - t) + x, sumBigger);
    error += lost;
    sums.radiance[2u * slot] = vec4(t, 0.0);
    sums.radiance[2u * slot + 1u] = vec4(error, 0.0);
    vec3 emitted = side == kAtlasFront ? AtlasTexels(push.texels).texels[texel].emission : vec3(0.0);
    emitted += AtlasRadiance(push.direct).radiance[slot].rgb;
    AtlasRadiance(push.sender).radiance[slot] = vec4(emitted + (t + error) * push.inverseTotalWeight, 0.0);
}
