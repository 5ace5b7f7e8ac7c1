#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, view raster: the scene drawn on the atlas's vertices (GpuScene with an atlas link),
// carrying each vertex's atlas uv and page to the camera's visible surface.
#include "shared/GpuTypes.h"
#include "modes/atlas/AtlasShared.h"

layout(location = 0) in vec4 inPositionU;
layout(location = 1) in vec4 inNormalV;
layout(location = kAtlasVertexLocationUv) in vec2 inAtlasUv;
layout(location = kAtlasVertexLocationPage) in uint inPage;

layout(push_constant) uniform PushBlock { AtlasViewPush push; };

layout(location = 0) out vec2 outAtlasUv;
layout(location = 1) flat out uint outPage;

void main() {
    outAtlasUv = inAtlasUv;
    outPage = inPage;
    gl_Position = push.viewProj * (push.model * vec4(inPositionU.xyz, 1.0));
}
