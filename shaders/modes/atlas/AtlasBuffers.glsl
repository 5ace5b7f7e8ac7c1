// Buffer references of mode atlas (shaders/modes/atlas/AtlasShared.h) and the texel a bundle hit
// or camera sample falls in.
#ifndef BL_ATLAS_BUFFERS_GLSL
#define BL_ATLAS_BUFFERS_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "modes/atlas/AtlasShared.h"
#include "shared/GpuTypes.h"

layout(buffer_reference, std430, buffer_reference_align = 16) buffer AtlasTexels { AtlasTexel texels[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer AtlasTriangles { AtlasTriangle triangles[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer AtlasRadiance { vec4 radiance[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer AtlasReceived { uint words[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer AtlasDirectionBlock { AtlasDirection direction; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer AtlasCharts { int charts[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer AtlasMaterials { GpuMaterial materials[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer AtlasTouched { uint words[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer AtlasSenders { AtlasSenderRecord records[]; };

// Index of the texel that atlas uv `uv` (in [0, 1] of `page`) falls in: floor(uv * size), the same
// rule the host's texel areas (modes/atlas/AtlasTables.h) integrate over.
uint blAtlasTexelIndex(vec2 uv, uint page, uint width, uint height) {
    ivec2 texel = clamp(ivec2(floor(uv * vec2(width, height))), ivec2(0), ivec2(width, height) - 1);
    return (page * height + uint(texel.y)) * width + uint(texel.x);
}

// Texel of a bundle hit, from its triangle's atlas uvs and the hit's barycentrics.
uint blAtlasHitTexel(BundleHit hit, uvec2 triangles, uint width, uint height) {
    AtlasTriangle tri = AtlasTriangles(triangles).triangles[hit.id];
    vec2 b = unpackUnorm2x16(hit.barycentric);
    vec2 uv = (1.0 - b.x - b.y) * tri.uv0 + b.x * tri.uv1 + b.y * tri.uv2;
    return blAtlasTexelIndex(uv, tri.page, width, height);
}

// Side of a bundle node's surface that faces -omega (toward smaller depths) and +omega, from the
// node's `next` word: the face bit is set when the triangle's front faces -omega.
uint blAtlasSideFacingBackward(uint next) { return (next & kBundleFrontFaceBit) != 0u ? kAtlasFront : kAtlasBack; }
uint blAtlasSideFacingForward(uint next) { return (next & kBundleFrontFaceBit) != 0u ? kAtlasBack : kAtlasFront; }

// The sender radiance of texel side `slot` in direction `dir` (AtlasDirection), split into what
// its emitter sends (`emitted`: the front side's emission) and what it reflects (`reflected`).
// Interleaved: base (emission + direct) + sum / W of the directions before this one (the two
// channels where split) + the glossy transfer the previous direction stored; the same floating-
// point steps the update once wrote a sender atlas with. Bounce: the pass's fixed sender, all in
// `reflected`.
void blAtlasSenderParts(AtlasDirection dir, uint slot, out vec3 emitted, out vec3 reflected) {
    emitted = vec3(0.0);
    if (dir.transfer == kAtlasTransferBounce) {
        reflected = AtlasRadiance(dir.fixedSender).radiance[slot].rgb;
        return;
    }
    AtlasSenderRecord record = AtlasSenders(dir.senders).records[slot];
    vec3 glossy = record.tag == dir.previous ? record.glossy : vec3(0.0);
    precise vec3 mean = record.sum * dir.scale;
    if (dir.split != 0u) {
        if (slot % kAtlasSides == kAtlasFront) {
            emitted = AtlasTexels(dir.texels).texels[slot / kAtlasSides].emission;
        }
        AtlasRadiance indirect = AtlasRadiance(dir.sumsIndirect);
        mean += (indirect.radiance[2u * slot].rgb + indirect.radiance[2u * slot + 1u].rgb) * dir.indirectScale;
    }
    precise vec3 sum = record.base + mean + glossy;
    reflected = sum;
}

vec3 blAtlasSender(AtlasDirection dir, uint slot) {
    vec3 emitted, reflected;
    blAtlasSenderParts(dir, slot, emitted, reflected);
    return emitted + reflected;
}

// Puts texel side `slot` on this direction's touched list once (word kAtlasReceivedTouched of its
// received slot is the mark, cleared by the update).
void blAtlasTouch(uvec2 receivedAddress, uvec2 touchedAddress, uint slot) {
    AtlasReceived received = AtlasReceived(receivedAddress);
    uint mark = kAtlasReceivedWords * slot + kAtlasReceivedTouched;
    if (received.words[mark] != 0u || atomicExchange(received.words[mark], 1u) != 0u) {
        return;
    }
    AtlasTouched list = AtlasTouched(touchedAddress);
    uint k = atomicAdd(list.words[0], 1u);
    list.words[kAtlasTouchedHeader + k] = slot;
    if (k % kAtlasGroupSize == 0u) {
        atomicAdd(list.words[1], 1u);
    }
}

#endif
