// Visibility along a depth map's direction omega (bundle/DepthMapPass: per pixel the depth of the
// surface nearest a light at +infinity along omega and that surface's shading normal; -inf where
// nothing is). The caller defines BL_DEPTH_MAP_TEXEL(pixel, layer), the map's vec4 (depth, normal)
// at a pixel of the frame's tile, first.
//
// x (normal n of either sign, cosine = n . omega) tests its own pixel's centre: anything beyond x's
// own plane there by blBundleSurfaceEpsilon occludes it (the map has no faces: winding plays no
// part). That box-filters the visibility over the pixel: light is lost and gained in strips half a
// pixel diagonal wide beside contact lines and outlines, and the mean is kept in open scenes.
//
// The centre alone leaks into closed rooms at their creases; the contact taps of x's footprint
// close that (bundle/Traversal.glsl, "Contact taps": the rule and what it leaves open).
#ifndef BL_BUNDLE_DEPTH_MAP_VISIBILITY_GLSL
#define BL_BUNDLE_DEPTH_MAP_VISIBILITY_GLSL
#include "bundle/Traversal.glsl"

// Whether x (in `pixel` of the frame's tile at `depth`, from blBundlePixel) is hidden by the
// surface at its own pixel's centre: beyond x's own plane there by blBundleSurfaceEpsilon.
bool blDepthMapCentreOccluded(BundleFrame frame, int layer, ivec2 pixel, vec3 x, float depth, vec3 n, float cosine) {
    return BL_DEPTH_MAP_TEXEL(pixel, layer).x >
           blBundleSurfaceDepth(frame, pixel, x, depth, n) + blBundleSurfaceEpsilon(frame, cosine);
}

// Whether x is hidden from the light along omega in map `layer`: its centre, then the contact taps.
bool blDepthMapOccluded(BundleFrame frame, int layer, ivec2 pixel, vec3 x, float depth, vec3 n, float cosine) {
    if (blDepthMapCentreOccluded(frame, layer, pixel, x, depth, n, cosine)) {
        return true;
    }
    float epsilon = blBundleSurfaceEpsilon(frame, cosine);
    vec3 lit = cosine < 0.0 ? -n : n;
    ivec2 taps[3];
    blBundleContactTaps(frame, x, pixel, taps);
    for (int i = 0; i < 3; ++i) {
        if (taps[i].x < 0) {
            continue;
        }
        vec4 texel = BL_DEPTH_MAP_TEXEL(taps[i], layer);
        if (!(texel.x > -3.0e38)) {
            continue; // depth -inf: nothing in that pixel
        }
        vec3 point = blBundlePixelRay(frame, vec2(taps[i]) + 0.5) + texel.x * frame.direction;
        if (blBundleContactAhead(point, texel.yzw, x, lit, abs(cosine), frame.direction, epsilon) >= 0.0 &&
            blBundleContactNearX(frame, point, texel.yzw, x, lit, cosine)) {
            return true;
        }
    }
    return false;
}

#endif
