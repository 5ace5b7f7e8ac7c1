// Where points fall in a bundle frame's pixel grid. Every projection of the build and of the
// queries goes through these functions, so a tile (which keeps its frame's origin and adds an
// integer pixel offset) sees exactly the pixels and depths the whole frame sees.
#ifndef BL_BUNDLE_PROJECTION_GLSL
#define BL_BUNDLE_PROJECTION_GLSL
#include "shared/BundleTypes.h"

// Pixel coordinates of p in the frame's whole grid (not the tile's) and p's depth.
vec3 blBundleGridPosition(BundleFrame frame, vec3 p) {
    vec3 rel = p - frame.origin;
    return vec3(dot(rel, frame.axisX) / frame.pixelSize, dot(rel, frame.axisY) / frame.pixelSize,
                dot(rel, frame.direction));
}

// The tile's pixel whose ray passes nearest to p, and p's depth; false outside the tile. The floor
// is taken in the whole grid, then the integer offset removed: neighbouring tiles partition points
// exactly.
bool blBundlePixel(BundleFrame frame, vec3 p, out ivec2 pixel, out float depth) {
    vec3 g = blBundleGridPosition(frame, p);
    depth = g.z;
    pixel = ivec2(floor(g.xy)) - ivec2(frame.tileX, frame.tileY);
    return pixel.x >= 0 && pixel.y >= 0 && pixel.x < int(frame.width) && pixel.y < int(frame.height);
}

// The ray of the tile's pixel at `fragCoord` (gl_FragCoord.xy: the pixel centre) at depth 0.
vec3 blBundlePixelRay(BundleFrame frame, vec2 fragCoord) {
    vec2 g = fragCoord + vec2(frame.tileX, frame.tileY); // exact: integer + k/2
    return frame.origin + g.x * frame.pixelSize * frame.axisX + g.y * frame.pixelSize * frame.axisY;
}

// The build's viewport size: the next powers of two at or above the whole grid (the host sets the
// same viewport, placed at minus the tile's offset: bundleViewport), so clip -> window is exact.
vec2 blBundleViewportExtent(BundleFrame frame) {
    return vec2(frame.gridWidth <= 1u ? 1u : 1u << (findMSB(frame.gridWidth - 1u) + 1),
                frame.gridHeight <= 1u ? 1u : 1u << (findMSB(frame.gridHeight - 1u) + 1));
}

// p's position in the whole grid snapped to 1/kBundleSubpixelGrid of a pixel (where both build
// backends place a vertex), and p's depth.
vec2 blBundleSnappedGrid(BundleFrame frame, vec3 p, out float depth) {
    vec3 g = blBundleGridPosition(frame, p);
    depth = g.z;
    return round(g.xy * kBundleSubpixelGrid) / kBundleSubpixelGrid;
}

// Clip position of p for the build's rasterizer, and p's depth. Every tile outputs the whole
// frame's clip position (its viewport is shifted instead), so clipping cuts the same triangles at
// the same places; the window position is snapped to 1/kBundleSubpixelGrid of a pixel first, after
// which the viewport transform is exact. A tile thus rasterizes each triangle exactly as the whole
// frame does (the rasterizer's own snapping agrees too, whatever its subpixel precision).
vec4 blBundleClipPosition(BundleFrame frame, vec3 p, out float depth) {
    vec2 window = blBundleSnappedGrid(frame, p, depth);
    vec2 ndc = window * (2.0 / blBundleViewportExtent(frame)) - 1.0;
    return vec4(ndc, (depth - frame.depthNear) / (frame.depthFar - frame.depthNear), 1.0);
}
#endif
