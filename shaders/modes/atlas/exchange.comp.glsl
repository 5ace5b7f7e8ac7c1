#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, one direction's radiance exchange ([HHGM10] Eq. 3; EQUATIONS.md section 4;
// the estimator is derived in modes/atlas/AtlasMode.h). One invocation per bundle pixel walks its
// depth-sorted list: consecutive hits y (shallower) and x (deeper) see each other along omega, so
// x's side facing -omega receives the sender radiance of y's side facing +omega and y's side facing
// +omega receives x's side facing -omega. The first hit's -omega side and the last hit's +omega
// side see the environment. Each receiver texel T adds
//   albedo_T * L_sender * a_pix / (pi p_r) / A_T
// (direction.weight = a_pix / (pi p_r), 1 / A_T per texel): the flux of the bundle pixel's ray, so
// that summed over the pixels hitting T and averaged over directions it is T's reflected radiance.
#include "modes/atlas/AtlasBuffers.glsl"
#include "bundle/Traversal.glsl"

layout(local_size_x = kAtlasGroupSize) in;
layout(push_constant) uniform PushBlock { AtlasExchangePush push; };

// Texel of a bundle node, from its triangle's atlas uvs and the hit's barycentrics.
uint texelOf(BundleHitPayload hits, uint node) {
    BundleHit hit = hits.hits[node];
    AtlasTriangle tri = AtlasTriangles(push.triangles).triangles[hit.id];
    vec2 b = unpackUnorm2x16(hit.barycentric);
    vec2 uv = (1.0 - b.x - b.y) * tri.uv0 + b.x * tri.uv1 + b.y * tri.uv2;
    return blAtlasTexelIndex(uv, tri.page, push.width, push.height);
}

// Side of a node's surface that faces -omega (toward smaller depths) and +omega. The face bit is
// set when the triangle's front faces -omega.
uint sideFacingBackward(uint next) { return (next & kBundleFrontFaceBit) != 0u ? kAtlasFront : kAtlasBack; }
uint sideFacingForward(uint next) { return (next & kBundleFrontFaceBit) != 0u ? kAtlasBack : kAtlasFront; }

// received[texel side] += value, three float adds by compare-and-swap (the device layer enables no
// float atomics; lavapipe's threads rarely collide on one texel).
void atomicAddRadiance(uint slot, vec3 value) {
    AtlasReceived received = AtlasReceived(push.received);
    for (uint c = 0u; c < 3u; ++c) {
        uint word = 4u * slot + c;
        uint expected = received.words[word];
        for (;;) {
            uint desired = floatBitsToUint(uintBitsToFloat(expected) + value[c]);
            uint found = atomicCompSwap(received.words[word], expected, desired);
            if (found == expected) {
                break;
            }
            expected = found;
        }
    }
}

void receive(uint texel, uint side, vec3 incoming, float weight) {
    AtlasTexel t = AtlasTexels(push.texels).texels[texel];
    vec3 value = t.albedo * incoming * (weight * t.inverseArea);
    if (t.inverseArea > 0.0 && any(greaterThan(value, vec3(0.0)))) {
        atomicAddRadiance(kAtlasSides * texel + side, value);
    }
}

void main() {
    BundleFrame frame = blBundlePoolFrame(push.pool, 0u);
    uint pixel = gl_GlobalInvocationID.x;
    if (pixel >= frame.width * frame.height) {
        return;
    }
    // The pool contract: a build that ran out of nodes left lists incomplete; the mode grows the
    // pool and redoes the direction, so nothing of this one may be added.
    if (blBundlePoolOverflowed(BundleCounterBlock(push.pool.counters))) {
        return;
    }
    AtlasDirection dir = AtlasDirectionBlock(push.direction).direction;
    BundleNodes nodes = BundleNodes(push.pool.nodes);
    BundleHitPayload hits = BundleHitPayload(push.pool.payload);
    AtlasRadiance sender = AtlasRadiance(push.sender);
    uint head = blBundlePoolHeads(push.pool, 0u).heads[pixel] & kBundleIndexMask;
    if (head == kBundleNil) {
        return;
    }
    // First hit: its -omega side looks out of the scene.
    uint y = head;
    uint yNext = nodes.nodes[y].next;
    uint yTexel = texelOf(hits, y);
    receive(yTexel, sideFacingBackward(yNext), dir.environmentBackward, dir.weight);
    for (uint x = yNext & kBundleIndexMask; x != kBundleNil;) {
        uint xNext = nodes.nodes[x].next;
        uint xTexel = texelOf(hits, x);
        uint ySide = sideFacingForward(yNext);
        uint xSide = sideFacingBackward(xNext);
        vec3 fromY = sender.radiance[kAtlasSides * yTexel + ySide].rgb;
        vec3 fromX = sender.radiance[kAtlasSides * xTexel + xSide].rgb;
        receive(xTexel, xSide, fromY, dir.weight);
        receive(yTexel, ySide, fromX, dir.weight);
        y = x;
        yNext = xNext;
        yTexel = xTexel;
        x = xNext & kBundleIndexMask;
    }
    // Last hit: its +omega side looks out of the scene.
    receive(yTexel, sideFacingForward(yNext), dir.environmentForward, dir.weight);
}
