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

#endif
