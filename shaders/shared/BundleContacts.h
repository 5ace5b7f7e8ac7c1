// The geometry by which a bundle walk (bundle/Traversal.glsl) judges the fragments near a point x,
// shared with the settings check's replay on the host (modes/SettingTrades.cpp,
// bundleVisibilityError), so that the check judges by the rule the shaders run.
//
// Names: omega the bundle direction; a fragment's point is where its pixel's centre ray meets its
// surface, m its facet's normal (either sign); x travels along d = +-omega; lit is x's normal
// turned to d's side and litCosine = |n . omega|; epsilon is the own-surface tolerance
// (blBundleOwnSurfaceTolerance), a distance along d.
#ifndef BL_SHARED_BUNDLE_CONTACTS_H
#define BL_SHARED_BUNDLE_CONTACTS_H
#include "BundleTypes.h"

BL_NAMESPACE_BEGIN

// The depth at which x's own ray (x = the centre ray's point at x's depth + e, e perpendicular to
// omega) crosses the plane with normal m through the centre ray's point at depth t. Grazing planes:
// the shift is capped at kBundleMaxOwnSurfaceTangent |e| (where |m . omega| < 0.083).
BL_INLINE float blBundlePlaneCrossing(vec3 omega, float t, vec3 e, vec3 m) {
    float c = dot(m, omega);
    float rise = dot(e, m); // the plane lies rise / c deeper on the centre ray than on x's ray
    float limit = kBundleMaxOwnSurfaceTangent * length(e);
    if (abs(rise) >= limit * abs(c)) {
        return t - (rise * c >= 0.0f ? limit : -limit);
    }
    return t - rise / c;
}

// How far past x a fragment's crossing must lie to count, the same for every fragment whatever its
// winding: depthEpsilon (float rounding of coordinates at the scene's scale and offset) over
// |n . omega| (a crossing divides a coordinate's rounding by it: x's own plane far from the origin
// otherwise shadows itself), plus what the interpolated-depth build can move a plane at the
// centre ray (vertices snapped to 1/kBundleSubpixelGrid px: that much times the plane's slope).
// Nothing real is skipped beyond that: closer is a contact.
BL_INLINE float blBundleOwnSurfaceTolerance(float depthEpsilon, float pixelSize, float cosine) {
    float c = max(abs(cosine), 1.0f / kBundleMaxOwnSurfaceTangent);
    float tangent = min(sqrt(max(0.0f, 1.0f - c * c)) / c, kBundleMaxOwnSurfaceTangent);
    return depthEpsilon / c + pixelSize * tangent / kBundleSubpixelGrid;
}

// The footprint's diagonal on x's plane (cosine = n . omega): sqrt(2) px / |cosine|, tangent
// capped; how near x a surface must be to count as x's neighbourhood.
BL_INLINE float blBundleReach(float pixelSize, float cosine) {
    return 1.41421356f * pixelSize * min(1.0f / max(abs(cosine), 1.0e-6f), kBundleMaxOwnSurfaceTangent);
}

// Rules (a) and (b) of the contact taps (bundle/Traversal.glsl): the surface through `point` lies
// in front of x's plane, and x's ray along d crosses its plane beyond epsilon; the crossing's
// distance along d, or -1.
BL_INLINE float blBundleContactAhead(vec3 point, vec3 m, vec3 x, vec3 lit, float litCosine, vec3 d, float epsilon) {
    float facing = dot(m, d);
    if (facing == 0.0f) {
        return -1.0f;
    }
    m = facing < 0.0f ? -m : m; // toward d: winding plays no part
    float ahead = dot(point - x, lit);
    float above = dot(point - x, m);
    return ahead > epsilon * litCosine && above > epsilon * abs(facing) ? above / abs(facing) : -1.0f;
}

// Rule (c) for the walks, which put the hit on the surface's plane: whether the plane through
// `anchor` (normal anchorNormal) and the plane through `point` (normal m) meet along a line that
// passes within sqrt(2) px (the diagonal of the 2x2 cell of pixel centres around the anchor's
// projection; a line crossing the cell passes that near every corner) of both points, measured in
// projection along omega. Parallel planes never meet. Both points: a face whose plane meets x's
// near x but which stays far away in its plane would put the hit in the air.
BL_INLINE bool blBundleContactNearBoth(vec3 omega, float pixelSize, vec3 point, vec3 m, vec3 anchor, vec3 anchorNormal) {
    vec3 line = cross(anchorNormal, m);
    float sine = length(line);
    if (sine < 1.0e-4f) {
        return false;
    }
    line /= sine;
    // Each point's distance to the line within its own plane, then that offset's projection.
    float anchorToLine = abs(dot(point - anchor, m)) / sine;
    float pointToLine = abs(dot(anchor - point, anchorNormal)) / sine;
    float c0 = dot(cross(line, anchorNormal), omega);
    float c1 = dot(cross(line, m), omega);
    float limit = 1.41421356f * pixelSize;
    return anchorToLine * sqrt(max(0.0f, 1.0f - c0 * c0)) <= limit && pointToLine * sqrt(max(0.0f, 1.0f - c1 * c1)) <= limit;
}

// The near end's gate. The taps' rule alone takes every concave crease between small facets for a
// room's crease, and x's ray then crosses a neighbour's plane beyond its facet (a flat-shaded
// heightfield under a sky read 0.954 of the reference in skylight at 128^2, the env-lit bunny 0.96
// in red). So the taps speak at x's end only where x's own centre ray leaves x's neighbourhood
// open: it shows nothing near x on x's side of the tap's plane (it passed outside x's room), or it
// shows what makes the neighbourhood a room's. A fragment of x's own list is, for the gate:
BL_CONST uint kBundleFragmentAway = 0u;      // says nothing: beyond the reach behind x, or within
                                             // it on a plane x's ray crosses ahead that the walk
                                             // took or that is a convex edge's other face
BL_CONST uint kBundleFragmentNeighbour = 1u; // within reach, on a plane x's ray does not cross ahead
                                             // (x's surface, neighbours falling away from it)
BL_CONST uint kBundleFragmentRoom = 2u;      // within reach on a plane x's ray crosses ahead but
                                             // nearer than what the walk found (`walkFound`, along
                                             // d) and not behind x's plane: a crease the walk
                                             // refused; or farther than the reach ahead
// `along`: the fragment's depth less x's (along omega); `lateralSquared`: x's squared distance to
// its centre ray; `dir`: d = dir omega.
BL_INLINE uint blBundleNearFragment(vec3 point, vec3 m, float along, float lateralSquared, vec3 x, vec3 d, float dir,
                                    vec3 lit, float litCosine, float epsilon, float reach, float walkFound) {
    if (along * along + lateralSquared > reach * reach) {
        return dir * along > 0.0f ? kBundleFragmentRoom : kBundleFragmentAway;
    }
    float facing = dot(m, d);
    float crossing = facing != 0.0f ? dot(point - x, m) / facing : -1.0f;
    if (crossing <= epsilon) {
        return kBundleFragmentNeighbour;
    }
    bool behind = dot(point - x, lit) < -epsilon * litCosine;
    return crossing < walkFound - epsilon && !behind ? kBundleFragmentRoom : kBundleFragmentAway;
}

// Whether a neighbour's point `near` lies on x's side of the plane through `point` (normal m) by
// more than `tolerance`.
BL_INLINE bool blBundleOnXsSide(vec3 near, vec3 point, vec3 m, vec3 x, float tolerance) {
    float side = dot(near - point, m);
    return side * dot(x - point, m) > 0.0f && abs(side) > tolerance;
}

BL_NAMESPACE_END
#endif
