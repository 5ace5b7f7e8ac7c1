// Visibility along a depth map's direction omega (bundle/DepthMapPass: per pixel the depth of the
// surface nearest a light at +infinity along omega and the plane of that surface's facet, its
// geometric normal; -inf where nothing is). The caller defines BL_DEPTH_MAP_TEXEL(pixel, layer),
// the map's vec4 (depth, normal) at a pixel of the frame's tile, first.
//
// x (normal n of either sign, cosine = n . omega) tests its own pixel's centre: the surface there
// hides x where x's own ray crosses both x's plane through it and its own facet's plane beyond x
// by blBundleSurfaceEpsilon (the map has no faces: winding plays no part). x's plane alone took
// x's own facet, seen at the centre up to 0.71 px away, as rising in front of x wherever x's
// smooth normal tilts from the facet, and a finely tessellated surface's neighbouring facets
// wherever they meet x's at a concave crease; the facet's own plane places its surface exactly,
// and a real occluder lies beyond both. That box-filters the visibility over the pixel: light is
// lost and gained in strips half a pixel diagonal wide beside contact lines and outlines, and the
// mean is kept in open scenes.
//
// The centre alone leaks into closed rooms at their creases; the contact taps of x's footprint
// close that (bundle/Traversal.glsl, "Contact taps": the rule and what it leaves open). They are
// asked only where the centre shows nothing within the footprint's reach of x (nothing, or a
// surface far behind: the centre ray passed outside x's room). Where it shows x's own surface or
// its neighbours, the taps' rule saw every concave crease between facets as a room's crease.
// Measured on the env-lit bunny (144k facets, 512^2 maps, raster's direct light, 64^2, 20 s):
// 0.913 of the reference before, 0.955 with the facets' planes, 0.990 with the taps kept to
// nothing near x; RasterScenes.EnvironmentLightsCurvedAndRoughMeshesAsTheReferenceDoes holds both.
#ifndef BL_BUNDLE_DEPTH_MAP_VISIBILITY_GLSL
#define BL_BUNDLE_DEPTH_MAP_VISIBILITY_GLSL
#include "bundle/Traversal.glsl"

// Whether the surface of `texel` (x's own pixel's centre, already read) hides x (in `pixel` of the
// frame's tile at `depth`, from blBundlePixel): x's ray crosses x's own plane through it and its
// facet's plane beyond x by blBundleSurfaceEpsilon.
bool blDepthMapTexelHides(BundleFrame frame, vec4 texel, ivec2 pixel, vec3 x, float depth, vec3 n, float cosine) {
    float epsilon = blBundleSurfaceEpsilon(frame, cosine);
    return texel.x > blBundleSurfaceDepth(frame, pixel, x, depth, n) + epsilon &&
           texel.x > blBundleSurfaceDepth(frame, pixel, x, depth, texel.yzw) + epsilon;
}

bool blDepthMapCentreOccluded(BundleFrame frame, int layer, ivec2 pixel, vec3 x, float depth, vec3 n, float cosine) {
    return blDepthMapTexelHides(frame, BL_DEPTH_MAP_TEXEL(pixel, layer), pixel, x, depth, n, cosine);
}

// Whether x is hidden from the light along omega in map `layer`: its centre, then, where the
// centre shows nothing within the footprint's reach of x (blBundleFootprintReach), the contact
// taps.
bool blDepthMapOccluded(BundleFrame frame, int layer, ivec2 pixel, vec3 x, float depth, vec3 n, float cosine) {
    vec4 centre = BL_DEPTH_MAP_TEXEL(pixel, layer);
    if (blDepthMapTexelHides(frame, centre, pixel, x, depth, n, cosine)) {
        return true;
    }
    if (centre.x > -3.0e38) {
        vec3 centrePoint = blBundlePixelRay(frame, vec2(pixel) + 0.5) + centre.x * frame.direction;
        if (distance(centrePoint, x) <= blBundleFootprintReach(frame, cosine)) {
            return false;
        }
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
