#version 460
#extension GL_GOOGLE_include_directive : require
// Mode multibounce, imperfect bundles: the points of one textured material look their albedo up in
// its texture at their UV (the poster keeps texture detail on the splats; here per point, the
// texture at the splat's centre). One dispatch per textured material after points.comp; points of
// other materials keep what that pass wrote.
#include "modes/multibounce/MultibounceShared.h"

layout(local_size_x = kMultibouncePointsGroupSize) in;

layout(set = 0, binding = kMultibouncePointsBindingSplats) readonly buffer SplatBlock { BundleSplat splats[]; };
layout(set = 0, binding = kMultibouncePointsBindingPoints) buffer PointBlock { MultibouncePoint points[]; };
layout(set = kMultibouncePointsTextureSet, binding = kMultibouncePointsBindingTexture) uniform sampler2D albedoTexture;
layout(push_constant) uniform PushBlock { MultibouncePointsPush push; };

void main() {
    uint index = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * kMultibouncePointsGroupSize) + gl_GlobalInvocationID.x;
    if (index >= push.count || splats[index].material != push.textured) {
        return;
    }
    vec2 uv = points[index].uv;
    // OBJ texture coordinates have v = 0 at the bottom; image row 0 is the top (as the G-buffer).
    vec3 albedo = textureLod(albedoTexture, vec2(uv.x, 1.0 - uv.y), 0.0).rgb;
    points[index].albedo = uvec2(packHalf2x16(albedo.rg), packHalf2x16(vec2(albedo.b, 0.0)));
}
