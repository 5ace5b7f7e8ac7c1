#version 460
#extension GL_GOOGLE_include_directive : require
// Mode atlas, view raster: atlas uv, page and the side the camera sees (gl_FrontFacing, the same
// test as the G-buffer's one-sided emission).
#include "modes/atlas/AtlasShared.h"

layout(location = 0) in vec2 inAtlasUv;
layout(location = 1) flat in uint inPage;
layout(location = 0) out vec4 outView;

void main() {
    uint side = gl_FrontFacing ? kAtlasFront : kAtlasBack;
    outView = vec4(inAtlasUv, float(inPage), float(side + 1u));
}
