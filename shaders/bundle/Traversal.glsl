// Traversal of bundle lists. Unsorted lists ([TO12s] Program 1): queries walk the whole list keeping
// the best candidate. Lists ordered by the pool's sort pass: the walk stops at the first fragment
// past the query, and neighbours are one step away on either side.
#ifndef BL_BUNDLE_TRAVERSAL_GLSL
#define BL_BUNDLE_TRAVERSAL_GLSL
#include "bundle/BundleBuffers.glsl"
#include "bundle/Projection.glsl"
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
// fragment counts from blBundleSurfaceEpsilon past x on. m is the fragment's shading normal from
// the hit payload (a flat face's plane; on smooth meshes close to it), or, without a payload,
// x's own normal n (every fragment taken parallel to x's plane: x's surface, coincident faces and
// thin walls still right, a corner's other wall seen as the centre ray meets it).

// The depth at which x's own ray (x = the centre ray's point at x's depth + e, e perpendicular to
// omega) crosses the plane with normal m through the centre ray's point at depth t. Grazing planes:
// the shift is capped at kBundleMaxOwnSurfaceTangent |e| (where |m . omega| < 0.083).
float blBundleCrossing(BundleFrame frame, float t, vec3 e, vec3 m) {
    float c = dot(m, frame.direction);
    float rise = dot(e, m); // the plane lies rise / c deeper on the centre ray than on x's ray
    float limit = kBundleMaxOwnSurfaceTangent * length(e);
    if (abs(rise) >= limit * abs(c)) {
        return t - (rise * c >= 0.0 ? limit : -limit);
    }
    return t - rise / c;
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
    float c = max(abs(cosine), 1.0 / kBundleMaxOwnSurfaceTangent);
    float tangent = min(sqrt(max(0.0, 1.0 - c * c)) / c, kBundleMaxOwnSurfaceTangent);
    return frame.depthEpsilon / c + frame.pixelSize * tangent / kBundleSubpixelGrid;
}

// The next surface along dir * omega (dir = +1 or -1) from x (pixel and depth from blBundlePixel,
// normal n of either sign), kBundleNil if none: the fragment whose plane x's own ray crosses
// first beyond blBundleSurfaceEpsilon, faces ignored (reflection is two-sided; emission's front
// face is the caller's test). `payload`: the pool has hit payloads (`hits`), whose normals give
// the planes and whose ids let x's own triangle `own` be skipped by identity (kBundleNil: no
// identity, e.g. splats, whose ids are point indices). Unsorted and sorted lists alike (the
// crossing order can differ from the list's by a fraction of a pixel: every node is looked at).
// `crossing`: the depth at which x's ray meets the found fragment's plane, so the caller can put
// the hit on x's own ray (x + (crossing - depth) omega): the fragment's centre-ray point can lie
// across a wall from x where the wall meets x's surface within the pixel.
uint blBundleSurfaceNearest(BundleNodes nodes, uint head, BundleHitPayload hits, bool payload, uint own,
                            BundleFrame frame, ivec2 pixel, vec3 x, float depth, vec3 n, float dir,
                            out float crossing) {
    vec3 e = blBundleCentreOffset(frame, pixel, x, depth);
    float epsilon = blBundleSurfaceEpsilon(frame, dot(n, frame.direction));
    uint best = kBundleNil;
    float bestDistance = 3.0e38;
    crossing = depth;
    for (uint i = head; i != kBundleNil;) {
        BundleNode node = nodes.nodes[i];
        vec3 m = n;
        bool mine = false;
        if (payload) {
            BundleHit hit = hits.hits[i];
            m = blUnpackOctahedral(hit.normal);
            mine = hit.id == own;
        }
        float distance = dir * (blBundleCrossing(frame, node.depth, e, m) - depth);
        if (distance > epsilon && distance < bestDistance && !mine) {
            best = i;
            bestDistance = distance;
            crossing = depth + dir * distance;
        }
        i = node.next & kBundleIndexMask;
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
