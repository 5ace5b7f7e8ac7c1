#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, one direction's radiance exchange ([HHGM10 Eq. 3]; papers/EQUATIONS.md;
// the estimator is derived in modes/atlas/AtlasMode.h). One invocation per bundle pixel walks its
// depth-sorted list: consecutive hits y (shallower) and x (deeper) see each other along omega, so
// x's side facing -omega receives the sender radiance of y's side facing +omega and y's side facing
// +omega receives x's side facing -omega (hits within the depth epsilon of each other are one
// group, see main). The first hit's -omega side and the last hit's +omega side see the
// environment. Each receiver texel T adds
//   albedo_T * L_sender * a_pix / (pi p_r) / A_T
// (direction.weight = a_pix / (pi p_r), 1 / A_T per texel): the flux of the bundle pixel's ray, so
// that summed over the pixels hitting T and averaged over directions it is T's reflected radiance.
//
// Glossy transfer atlas ([HHGM10] section 5.4): a receiver whose material has a glossy lobe also
// stores, for the next direction omega_{i+1}, what that lobe reflects of the same incoming light
// toward the one of +-omega_{i+1} on the receiving side's hemisphere:
//   L_sender f_glossy(n_s, d_in, o) a_pix / (p_r A_T) = pi weight L f_glossy / A_T
// (the Lambert term's rho / pi replaced by the lobe at the hit's shading normal). Summed over the
// pixels hitting T it is a one-direction estimate of T's glossy outgoing radiance toward o; the
// update adds it to T's sender for direction i + 1 only, and since that sender already holds what
// came in glossily at i, light travels through any number of glossy surfaces.
//
// Split channels (delay_indirect, [HHGM10] section 6.4): what the sender's emitter (and the
// environment) sends is received into the one-bounce channel (words 0..2), what it reflects into
// the multi-bounce channel (receivedIndirect), the latter only once indirect light is enabled.
// Every side that receives joins the direction's touched list (the update visits only those).
#include "modes/atlas/AtlasBuffers.glsl"
#include "bundle/Traversal.glsl"
#include "shared/Brdf.h"
#include "shared/Octahedral.h"

layout(local_size_x = kAtlasGroupSize) in;
layout(push_constant) uniform PushBlock { AtlasExchangePush push; };
layout(constant_id = kAtlasSpecSplit) const bool kSplit = true;
layout(constant_id = kAtlasSpecGlossy) const bool kGlossy = true;
layout(constant_id = kAtlasSpecBounce) const bool kBounce = false;

// The direction's words with what the pipeline's constants fix put in as constants (AtlasShared.h,
// kAtlasSpecSplit): the paths they rule out fold away wherever `dir` is read.
AtlasDirection specialized(AtlasDirection dir) {
    dir.split = kSplit ? dir.split : 0u;
    dir.glossy = kGlossy ? dir.glossy : 0u;
    dir.transfer = kBounce ? kAtlasTransferBounce : kAtlasTransferInterleaved;
    return dir;
}

// Texel of a bundle node.
uint texelOf(BundleHitPayload hits, uint node) {
    return blAtlasHitTexel(hits.hits[node], push.triangles, push.width, push.height);
}

// words[stride * slot + offset + c] += value[c], three float adds by compare-and-swap (the device
// layer enables no float atomics; lavapipe's threads rarely collide on one texel).
void atomicAddRadiance(uvec2 address, uint stride, uint slot, uint offset, vec3 value) {
    AtlasReceived received = AtlasReceived(address);
    blAtlasTouch(push.received, AtlasDirectionBlock(push.direction).direction.touched, slot);
    for (uint c = 0u; c < 3u; ++c) {
        uint word = stride * slot + offset + c;
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

// Texel side `side` of node `node` receives radiance arriving from direction `toward` (unit, away
// from the surface: -omega for the side facing backward, +omega forward): `incoming` from an
// emitter or the environment and `reflected` from a reflecting surface (one sum where not split).
void receive(BundleHitPayload hits, uint node, uint texel, uint side, vec3 emitted, vec3 reflected, vec3 toward,
             AtlasDirection dir) {
    vec3 incoming = emitted + reflected;
    AtlasTexel t = AtlasTexels(push.texels).texels[texel];
    if (!(t.inverseArea > 0.0) || !any(greaterThan(incoming, vec3(0.0)))) {
        return;
    }
    uint slot = kAtlasSides * texel + side;
    if (dir.split == 0u) {
        vec3 value = t.albedo * incoming * (dir.weight * t.inverseArea);
        if (any(greaterThan(value, vec3(0.0)))) {
            atomicAddRadiance(push.received, kAtlasReceivedWords, slot, 0u, value);
        }
    } else {
        vec3 one = t.albedo * emitted * (dir.weight * t.inverseArea);
        vec3 multi = t.albedo * reflected * (dir.weight * t.inverseArea);
        if (any(greaterThan(one, vec3(0.0)))) {
            atomicAddRadiance(push.received, kAtlasReceivedWords, slot, 0u, one);
        }
        if (any(greaterThan(multi, vec3(0.0)))) {
            atomicAddRadiance(dir.receivedIndirect, 4u, slot, 0u, multi);
        }
    }
    if (dir.glossy == 0u) {
        return;
    }
    BundleHit hit = hits.hits[node];
    GpuMaterial m = AtlasMaterials(push.materials).materials[hit.material & kBundleHitMaterialMask];
    if (m.specular.x + m.specular.y + m.specular.z <= 0.0) {
        return;
    }
    // The shading normal turned to the receiving side (the side faces `toward`), and the one of
    // +-next in that side's hemisphere: the direction the stored radiance leaves in at i + 1.
    vec3 n = blUnpackOctahedral(hit.normal);
    n = dot(n, toward) < 0.0 ? -n : n;
    vec3 leaving = dot(n, dir.next) >= 0.0 ? dir.next : -dir.next;
    vec3 lobe = blEvalBrdf(m, vec3(0.0), n, toward, leaving); // albedo 0: the glossy lobe alone
    vec3 glossy = kPi * dir.weight * t.inverseArea * lobe * incoming;
    if (any(greaterThan(glossy, vec3(0.0)))) {
        atomicAddRadiance(push.received, kAtlasReceivedWords, slot, kAtlasReceivedGlossy, glossy);
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
    AtlasDirection dir = specialized(AtlasDirectionBlock(push.direction).direction);
    BundleNodes nodes = BundleNodes(push.pool.nodes);
    BundleHitPayload hits = BundleHitPayload(push.pool.payload);
    uint head = blBundlePoolHeads(push.pool, 0u).heads[pixel] & kBundleIndexMask;
    if (head == kBundleNil) {
        return;
    }
    // Coincident fragments (depths within the frame's depth epsilon: a face and its duplicate, a
    // reversed copy, overlapping coplanar triangles, a box's bottom on the floor) are one boundary,
    // not a gap: every member's side facing -omega receives from the group before (the
    // environment at the list's start) and its side facing +omega from the group after; only the
    // first member sends back and the last sends on. Paired one by one instead, the members
    // exchanged with each other across zero distance, so which of them saw the room depended on
    // the sort's tie order (a reversed duplicate floor: image -3.3%, indirect -7%). Light still
    // never crosses the group: its inner sides receive but do not send. A group of one is the
    // plain pairing of consecutive hits.
    vec3 omega = frame.direction;
    // Before indirect light is enabled (split) surfaces send their emission only.
    float reflects = dir.split == 0u || dir.indirect != 0u ? 1.0 : 0.0;
    vec3 backEmitted = dir.environmentBackward, backReflected = vec3(0.0); // what arrives along +omega
    for (uint first = head; first != kBundleNil;) {
        uint last = first;
        uint after = nodes.nodes[first].next & kBundleIndexMask;
        while (after != kBundleNil && nodes.nodes[after].depth - nodes.nodes[first].depth <= frame.depthEpsilon) {
            last = after;
            after = nodes.nodes[after].next & kBundleIndexMask;
        }
        vec3 onEmitted = dir.environmentForward, onReflected = vec3(0.0); // what arrives along -omega
        if (after != kBundleNil) {
            uint afterSide = blAtlasSideFacingBackward(nodes.nodes[after].next);
            blAtlasSenderParts(dir, kAtlasSides * texelOf(hits, after) + afterSide, onEmitted, onReflected);
            onReflected *= reflects;
        }
        for (uint n = first;; n = nodes.nodes[n].next & kBundleIndexMask) {
            uint nNext = nodes.nodes[n].next;
            uint nTexel = texelOf(hits, n);
            receive(hits, n, nTexel, blAtlasSideFacingBackward(nNext), backEmitted, backReflected, -omega, dir);
            receive(hits, n, nTexel, blAtlasSideFacingForward(nNext), onEmitted, onReflected, omega, dir);
            if (n == last) {
                break;
            }
        }
        uint lastSide = blAtlasSideFacingForward(nodes.nodes[last].next);
        blAtlasSenderParts(dir, kAtlasSides * texelOf(hits, last) + lastSide, backEmitted, backReflected);
        backReflected *= reflects;
        first = after;
    }
}
