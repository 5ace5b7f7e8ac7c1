// Traversal of bundle lists. Unsorted lists ([TO12s] Program 1): queries walk the whole list keeping
// the best candidate. Lists ordered by the pool's sort pass: the walk stops at the first fragment
// past the query, and neighbours are one step away on either side.
#ifndef BL_BUNDLE_TRAVERSAL_GLSL
#define BL_BUNDLE_TRAVERSAL_GLSL
#include "bundle/BundleBuffers.glsl"
#include "bundle/Projection.glsl"
#include "shared/BundleContacts.h"
#include "shared/Octahedral.h"


uint blBundleHead(BundleHeads heads, BundleFrame frame, ivec2 pixel) {
    return heads.heads[uint(pixel.y) * frame.width + uint(pixel.x)] & kBundleIndexMask;
}

// How far from a point's depth its own surface can appear in its bundle pixel (the pixel centre's
// ray meets the point's plane up to a pixel away): frame.depthEpsilon + 1 px * tan(incidence),
// where `cosine` = |n . omega| for the point's normal n. Used by the face-bit walk (atlas) only.
float blBundleOwnSurfaceEpsilon(BundleFrame frame, float cosine) {
    float c = max(abs(cosine), 1.0 / kBundleMaxOwnSurfaceTangent);
    float tangent = min(sqrt(max(0.0, 1.0 - c * c)) / c, kBundleMaxOwnSurfaceTangent);
    return frame.depthEpsilon + kBundleOwnSurfacePixels * frame.pixelSize * tangent;
}

// True when a fragment faces the point it is seen from: a ray leaving a point along
// dir * omega (dir = +1 or -1) meets the front of a triangle whose front faces -dir * omega.
bool blBundleFacesBack(uint next, float dir) {
    bool frontFacesMinusOmega = (next & kBundleFrontFaceBit) != 0u;
    return dir > 0.0 ? frontFacesMinusOmega : !frontFacesMinusOmega;
}

// The one walk every query shares: the nearest fragment beyond depth d along dir * omega (dir = +1
// or -1), kBundleNil if none. A fragment facing the query counts from `facing` past d, one turning
// its back from `back` past d; fragments of triangle `own` (the hit payload's id; kBundleNil: no
// payload, nothing skipped by identity) never count. Sorted lists stop early.
uint blBundleWalk(BundleNodes nodes, uint head, float d, float dir, float facing, float back, BundleHitPayload hits,
                  uint own, bool sorted) {
    uint best = kBundleNil;
    float bestDistance = 3.0e38;
    for (uint i = head; i != kBundleNil;) {
        BundleNode n = nodes.nodes[i];
        float distance = dir * (n.depth - d);
        float threshold = blBundleFacesBack(n.next, dir) ? facing : back;
        if (distance > threshold && distance < bestDistance && (own == kBundleNil || hits.hits[i].id != own)) {
            best = i;
            bestDistance = distance;
            if (sorted && dir > 0.0) {
                break; // ascending depths: the first one past the point is the nearest
            }
        } else if (sorted && dir < 0.0 && n.depth > d) {
            break; // backwards: everything from here on is behind the query
        }
        i = n.next & kBundleIndexMask;
    }
    return best;
}

// The face-bit rule (atlas, whose gather keeps one side per face): fragments within `ownEpsilon`
// of d that turn their back on the query (the point's own surface, sampled half a pixel away at
// its own slope) are skipped; fragments facing the point count from frame.depthEpsilon on.
// Winding-dependent: the path-tracing modes use blBundleSurfaceNearest below instead.
uint blBundleNearest(BundleNodes nodes, uint head, float d, float dir, float ownEpsilon, BundleFrame frame) {
    return blBundleWalk(nodes, head, d, dir, frame.depthEpsilon, ownEpsilon, BundleHitPayload(uvec2(0u)), kBundleNil,
                        false);
}

// Sorted lists (after the sort pass): blBundleNearest's answer, stopping early.
uint blBundleSortedNearest(BundleNodes nodes, uint head, float d, float dir, float ownEpsilon, BundleFrame frame) {
    return blBundleWalk(nodes, head, d, dir, frame.depthEpsilon, ownEpsilon, BundleHitPayload(uvec2(0u)), kBundleNil,
                        true);
}

// ---- The surface convention of the path-tracing modes (multibounce, bidir, skylight) ----
// A query from a surface point x (its pixel and depth from blBundlePixel) finds the fragments of its
// bundle pixel, which were sampled on the pixel's centre ray, up to 0.71 px beside x's own ray.
// Ordering them by their depth on the centre ray against x's own depth made the walk depend on
// where x's plane meets that ray: x's own surface could lie ahead of x, a thin wall's far face
// too, and the old cure (a face-bit rule: fragments turning their back skipped up to 1 px * tan)
// made it depend on winding. Instead every fragment is placed where x's OWN ray crosses the
// fragment's plane (through its centre-ray point, normal m), and ordered by that depth: x's own
// plane crosses at x's depth whatever its winding, the far face of a thin wall behind x, the
// other wall of a corner whose plane the centre ray met beyond x's polygon behind x as well; a
// fragment counts from blBundleSurfaceEpsilon past x on. m is the normal of the fragment's facet
// from the hit payload (BundleHit::plane; its shading normal is not its plane on smooth meshes):
// every walk's pool carries it (multibounce, bidir, skylight). Taken parallel to x's own plane
// instead, a small concave facet beside x rose in front of it.

// The depth at which x's own ray (x = the centre ray's point at x's depth + e, e perpendicular to
// omega) crosses the plane with normal m through the centre ray's point at depth t. Grazing planes:
// the shift is capped at kBundleMaxOwnSurfaceTangent |e| (where |m . omega| < 0.083).
float blBundleCrossing(BundleFrame frame, float t, vec3 e, vec3 m) {
    return blBundlePlaneCrossing(frame.direction, t, e, m);
}

// x's offset from its bundle pixel's centre ray (|e| <= 0.71 px).
vec3 blBundleCentreOffset(BundleFrame frame, ivec2 pixel, vec3 x, float depth) {
    return x - (blBundlePixelRay(frame, vec2(pixel) + 0.5) + depth * frame.direction);
}

// Where the centre ray meets x's own tangent plane (normal n): a fragment at that centre-ray depth
// parallel to x's plane lies at x's depth on x's ray (for a shadow map, which has no payload).
float blBundleSurfaceDepth(BundleFrame frame, ivec2 pixel, vec3 x, float depth, vec3 n) {
    vec3 e = blBundleCentreOffset(frame, pixel, x, depth);
    return depth + (depth - blBundleCrossing(frame, depth, e, n));
}

// How far past x a fragment's crossing must lie to count, the same for every fragment whatever its
// winding: frame.depthEpsilon (float rounding of coordinates at the scene's scale and offset) over
// |n . omega| (a crossing divides a coordinate's rounding by it: x's own plane far from the origin
// otherwise shadows itself), plus what the interpolated-depth build can move a plane at the
// centre ray (vertices snapped to 1/kBundleSubpixelGrid px: that much times the plane's slope).
// Nothing real is skipped beyond that: closer is a contact.
float blBundleSurfaceEpsilon(BundleFrame frame, float cosine) {
    return blBundleOwnSurfaceTolerance(frame.depthEpsilon, frame.pixelSize, cosine);
}

// The next surface along dir * omega (dir = +1 or -1) from x (pixel and depth from blBundlePixel,
// normal n of either sign), kBundleNil if none: the fragment whose plane x's own ray crosses
// first beyond blBundleSurfaceEpsilon, faces ignored (reflection is two-sided; emission's front
// face is the caller's test). The hit payloads (`hits`) give the fragments' facet planes
// (BundleHit::plane), and their ids let x's own triangle `own` be skipped by identity (kBundleNil:
// no identity, e.g. splats, whose ids are point indices). Unsorted and sorted lists alike (the
// crossing order can differ from the list's by a fraction of a pixel: every node is looked at).
// `crossing`: the depth at which x's ray meets the found fragment's plane, so the caller can put
// the hit on x's own ray (x + (crossing - depth) omega): the fragment's centre-ray point can lie
// across a wall from x where the wall meets x's surface within the pixel.
uint blBundleSurfaceNearest(BundleNodes nodes, uint head, BundleHitPayload hits, uint own,
                            BundleFrame frame, ivec2 pixel, vec3 x, float depth, vec3 n, float dir,
                            out float crossing) {
    vec3 e = blBundleCentreOffset(frame, pixel, x, depth);
    float cosine = dot(n, frame.direction);
    float epsilon = blBundleSurfaceEpsilon(frame, cosine);
    // How far ahead of x's plane (along its normal on the travel side) the fragment's own point on
    // the centre ray lies, per unit of depth and at x's depth.
    float aheadPerDepth = abs(cosine);
    float aheadAtX = -dot(e, cosine * dir >= 0.0 ? n : -n);
    uint best = kBundleNil;
    float bestDistance = 3.0e38;
    crossing = depth;
    for (uint i = head; i != kBundleNil;) {
        BundleNode node = nodes.nodes[i];
        BundleHit hit = hits.hits[i];
        vec3 m = blUnpackOctahedral(hit.plane);
        bool mine = hit.id == own;
        // A fragment's plane crosses x's ray ahead of x also where the fragment lies behind x's
        // plane: the other face of a convex edge, sampled just past the edge, whose plane x's ray
        // meets in the air beyond it. The fragment must lie ahead of x's plane (the contact taps'
        // rule (a), below).
        bool ahead = aheadAtX + dir * (node.depth - depth) * aheadPerDepth > epsilon * aheadPerDepth;
        float distance = dir * (blBundleCrossing(frame, node.depth, e, m) - depth);
        if (distance > epsilon && distance < bestDistance && !mine && ahead) {
            best = i;
            bestDistance = distance;
            crossing = depth + dir * distance;
        }
        i = node.next & kBundleIndexMask;
    }
    return best;
}

// ---- Contact taps: a closed room's creases (both the depth maps and the bundle walks) ----
// Where a wall meets the ceiling of a closed room, the crease lies on the room's outline seen along
// omega, and a wall point x within half a pixel of it can find nothing ahead on its pixel's centre
// ray (it passes outside the room): light leaks in, paths escape. The other three pixels of x's
// 2x2 footprint (blBundleContactTaps: toward the half of its pixel x lies in; a line that parts x
// from its own centre leaves one of the four centres on x's side) then tell: a surface found
// through `point` on a tap's centre ray with normal m (either sign) hides x from travel direction
// d when
//   (a) it lies in front of x's plane (`lit`: x's normal on d's side, |n . omega| = litCosine),
//   (b) x's ray along d crosses its plane beyond the own-surface tolerance `epsilon`
//       (blBundleContactAhead: both), and
//   (c) the two planes meet within the footprint (blBundleContactNearX for visibility,
//       blBundleContactNearBoth for the walks, which also refuse surfaces seen within the tangent
//       cap of their plane: a plane nearly along omega crosses the footprint's depth in a fraction
//       of a pixel and says little about where its surface is).
// A crease inside a closed room meets all three. A convex edge fails (a) (the other face lies
// behind x's plane), the lit side of a contact line fails (b), an occluder's outline far beyond x
// fails (c) (its plane does not meet x's near x): open scenes keep the centre's answer there. What
// stays open: a hiding face that no centre of the footprint shows (seen nearly edge-on, or at the
// corner where three outlines meet; tests/core/bundle/ClosedBoxCreaseTest.cpp counts them).
// The walks ask the taps at x's end only behind a gate (shared/BundleContacts.h,
// blBundleNearFragment): a concave crease between small facets meets (a) to (c) as well.

// (a) and (b) above: blBundleContactAhead (shared/BundleContacts.h).

// The footprint's diagonal on x's plane (normal n, cosine = n . omega): sqrt(2) px / |cosine|,
// tangent capped; how near x a surface must be to count as x's neighbourhood (the depth maps'
// taps and their gate, bundle/DepthMapVisibility.glsl).
float blBundleFootprintReach(BundleFrame frame, float cosine) { return blBundleReach(frame.pixelSize, cosine); }

// (c) for visibility (the depth maps): whether the plane through `point` (normal m) meets x's
// plane (through x, normal n, cosine = n . omega) within sqrt(2) px / |cosine| of x, the footprint's
// diagonal on x's plane (tangent capped). A surface whose plane meets x's near x but which itself
// stays far away in its plane (a box's bottom face, high beside x's wall) can only darken x within
// the footprint of that surface's outline; and a closed room is kept dark also by a wall whose
// plane x's ray crosses just after the face it leaves through, which (c) for the walks refuses.
bool blBundleContactNearX(BundleFrame frame, vec3 point, vec3 m, vec3 x, vec3 n, float cosine) {
    float k = dot(m, n);
    float sine = sqrt(max(0.0, 1.0 - k * k));
    return abs(dot(point - x, m)) <= blBundleFootprintReach(frame, cosine) * sine;
}

// (c) for the walks (shared/BundleContacts.h).
bool blBundleContactNearBoth(BundleFrame frame, vec3 point, vec3 m, vec3 anchor, vec3 anchorNormal) {
    return blBundleContactNearBoth(frame.direction, frame.pixelSize, point, m, anchor, anchorNormal);
}

// The three taps of x's footprint (pixel: x's own, from blBundlePixel); a tap outside the frame's
// tile is returned as (-1, -1).
void blBundleContactTaps(BundleFrame frame, vec3 x, ivec2 pixel, out ivec2 taps[3]) {
    vec2 inPixel = fract(blBundleGridPosition(frame, x).xy);
    ivec2 step = ivec2(inPixel.x < 0.5 ? -1 : 1, inPixel.y < 0.5 ? -1 : 1);
    taps[0] = pixel + ivec2(step.x, 0);
    taps[1] = pixel + ivec2(0, step.y);
    taps[2] = pixel + step;
    for (int i = 0; i < 3; ++i) {
        if (taps[i].x < 0 || taps[i].y < 0 || taps[i].x >= int(frame.width) || taps[i].y >= int(frame.height)) {
            taps[i] = ivec2(-1);
        }
    }
}

// The near end's gate for a tap's surface through `point` (normal m): whether x's own centre ray
// leaves x's neighbourhood open to it (shared/BundleContacts.h, blBundleNearFragment): it shows a
// room around x, or no neighbour on x's side of that plane. Asked only for a tap that meets rules
// (a) to (c), which is rare: one more walk of x's list then. `walkFound`: what x's own list found,
// along d.
bool blBundleNearEndOpen(BundleNodes nodes, BundleHitPayload hits, uint head, BundleFrame frame, ivec2 pixel, vec3 x,
                         float depth, vec3 d, vec3 lit, float litCosine, float epsilon, float reach, float walkFound,
                         vec3 point, vec3 m) {
    vec3 ray = blBundlePixelRay(frame, vec2(pixel) + 0.5);
    vec3 e = x - (ray + depth * frame.direction);
    float lateralSquared = dot(e, e);
    float dir = dot(d, frame.direction) >= 0.0 ? 1.0 : -1.0;
    float tolerance = epsilon * abs(dot(m, d));
    bool neighbourOnXsSide = false;
    for (uint i = head; i != kBundleNil;) {
        BundleNode node = nodes.nodes[i];
        vec3 fragment = ray + node.depth * frame.direction;
        uint kind = blBundleNearFragment(fragment, blUnpackOctahedral(hits.hits[i].plane), node.depth - depth,
                                         lateralSquared, x, d, dir, lit, litCosine, epsilon, reach, walkFound);
        if (kind == kBundleFragmentRoom) {
            return true;
        }
        neighbourOnXsSide = neighbourOnXsSide ||
                            (kind == kBundleFragmentNeighbour && blBundleOnXsSide(fragment, point, m, x, tolerance));
        i = node.next & kBundleIndexMask;
    }
    return !neighbourOnXsSide;
}

// blBundleSurfaceNearest on a pool with hit payloads, with the footprint's taps (above) at both ends
// of x's segment: a tap's fragment that hides x across a crease near x (nothing ahead on x's own
// centre ray), or across a concave crease near the hit x's own list found, nearer than that hit
// (x's ray meets a floor just before the back wall whose plane the centre ray found: the crease
// where they meet lies within the footprint of the hit, (a) and (c) taken there with the hit's
// plane), wins; kBundleNil if nothing. Without the second, the next vertex went on the back wall's plane beyond
// the floor, outside a closed room. `hitPixel`: the pixel whose centre ray holds the fragment (x's
// own, or a tap's), for a caller that places the hit on that ray; `crossing` as
// blBundleSurfaceNearest (on x's own ray).
uint blBundleSurfaceNearestAcrossCreases(BundleNodes nodes, BundleHeads heads, BundleHitPayload hits, uint own,
                                         BundleFrame frame, ivec2 pixel, vec3 x, float depth, vec3 n, float dir,
                                         out float crossing, out ivec2 hitPixel) {
    hitPixel = pixel;
    uint best = blBundleSurfaceNearest(nodes, blBundleHead(heads, frame, pixel), hits, own, frame, pixel, x,
                                       depth, n, dir, crossing);
    float cosine = dot(n, frame.direction);
    vec3 d = dir * frame.direction;
    vec3 lit = dot(n, d) < 0.0 ? -n : n;
    float epsilon = blBundleSurfaceEpsilon(frame, cosine);
    // The far end: the own list's hit and its plane.
    bool found = best != kBundleNil;
    float bestDistance = found ? dir * (crossing - depth) : 3.0e38;
    float reach = blBundleFootprintReach(frame, cosine);
    vec3 hitPoint = found ? x + bestDistance * d : x;
    vec3 hitNormal = found ? blUnpackOctahedral(hits.hits[best].plane) : n;
    hitNormal = dot(hitNormal, d) > 0.0 ? -hitNormal : hitNormal; // toward x's side
    float hitCosine = abs(dot(hitNormal, frame.direction));
    float hitEpsilon = blBundleSurfaceEpsilon(frame, hitCosine) * hitCosine;
    float ownDistance = bestDistance;
    ivec2 taps[3];
    blBundleContactTaps(frame, x, pixel, taps);
    for (int t = 0; t < 3; ++t) {
        if (taps[t].x < 0) {
            continue;
        }
        vec3 ray = blBundlePixelRay(frame, vec2(taps[t]) + 0.5);
        for (uint i = blBundleHead(heads, frame, taps[t]); i != kBundleNil;) {
            uint index = i;
            BundleNode node = nodes.nodes[i];
            BundleHit hit = hits.hits[i];
            vec3 point = ray + node.depth * frame.direction;
            vec3 m = blUnpackOctahedral(hit.plane);
            bool usable = hit.id != own && abs(dot(m, frame.direction)) * kBundleMaxOwnSurfaceTangent >= 1.0;
            float distance = usable ? blBundleContactAhead(point, m, x, lit, abs(cosine), d, epsilon) : -1.0;
            i = node.next & kBundleIndexMask;
            if (distance < 0.0 || distance >= bestDistance) {
                continue; // most fragments: the crease tests below only for a nearer candidate
            }
            // The far end's crease must be concave as x sees it: the tap's surface lies on x's
            // side of the found plane (the side face of a convex edge whose top x's ray lands on
            // lies behind it, and its plane is crossed in the air above the edge).
            bool farEnd = found && distance < ownDistance && dot(point - hitPoint, hitNormal) > hitEpsilon &&
                          blBundleContactNearBoth(frame, point, m, hitPoint, hitNormal);
            // The near end, behind its gate.
            bool nearEnd = blBundleContactNearBoth(frame, point, m, x, lit) &&
                           blBundleNearEndOpen(nodes, hits, blBundleHead(heads, frame, pixel), frame, pixel, x, depth,
                                               d, lit, abs(cosine), epsilon, reach, ownDistance, point, m);
            if (farEnd || nearEnd) {
                best = index;
                bestDistance = distance;
                hitPixel = taps[t];
            }
        }
    }
    if (best != kBundleNil) {
        crossing = depth + dir * bestDistance;
    }
    return best;
}

// The next fragment in depth order after node `from` (by depth, ties broken by index), and the
// previous one; kBundleNil at the ends.
uint blBundleNext(BundleNodes nodes, uint head, uint from) {
    float d = nodes.nodes[from].depth;
    uint best = kBundleNil;
    float bestDepth = 3.0e38;
    for (uint i = head; i != kBundleNil;) {
        BundleNode n = nodes.nodes[i];
        bool after = n.depth > d || (n.depth == d && i > from);
        bool better = n.depth < bestDepth || (n.depth == bestDepth && i < best);
        if (after && better) {
            best = i;
            bestDepth = n.depth;
        }
        i = n.next & kBundleIndexMask;
    }
    return best;
}

uint blBundlePrevious(BundleNodes nodes, uint head, uint from) {
    float d = nodes.nodes[from].depth;
    uint best = kBundleNil;
    float bestDepth = -3.0e38;
    for (uint i = head; i != kBundleNil;) {
        BundleNode n = nodes.nodes[i];
        bool before = n.depth < d || (n.depth == d && i < from);
        bool better = n.depth > bestDepth || (n.depth == bestDepth && (best == kBundleNil || i > best));
        if (before && better) {
            best = i;
            bestDepth = n.depth;
        }
        i = n.next & kBundleIndexMask;
    }
    return best;
}

// The neighbours of node i in a sorted list, O(1): deeper along omega, and shallower (the
// `previous` array the sort pass fills). kBundleNil at the ends.
uint blBundleSortedNext(BundleNodes nodes, uint i) { return nodes.nodes[i].next & kBundleIndexMask; }
uint blBundleSortedPrevious(BundlePrevious previous, uint i) { return previous.previous[i]; }

#endif
