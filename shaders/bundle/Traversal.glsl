// Traversal of bundle lists. Unsorted lists ([TO12s] Program 1): queries walk the whole list keeping
// the best candidate. Lists ordered by the pool's sort pass: the walk stops at the first fragment
// past the query, and neighbours are one step away on either side.
#ifndef BL_BUNDLE_TRAVERSAL_GLSL
#define BL_BUNDLE_TRAVERSAL_GLSL
#include "bundle/BundleBuffers.glsl"
#include "bundle/Projection.glsl"


uint blBundleHead(BundleHeads heads, BundleFrame frame, ivec2 pixel) {
    return heads.heads[uint(pixel.y) * frame.width + uint(pixel.x)] & kBundleIndexMask;
}

// How far from a point's depth its own surface can appear in its bundle pixel (the pixel centre's
// ray meets the point's plane up to a pixel away): frame.depthEpsilon + 1 px * tan(incidence),
// where `cosine` = |n . omega| for the point's normal n.
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

// The nearest fragment beyond depth d along dir * omega (dir = +1 or -1), kBundleNil if none.
// Fragments within `ownEpsilon` of d that turn their back on the query (the point's own surface,
// sampled half a pixel away at its own slope) are skipped; fragments facing the point count from
// frame.depthEpsilon on.
uint blBundleNearest(BundleNodes nodes, uint head, float d, float dir, float ownEpsilon, BundleFrame frame) {
    uint best = kBundleNil;
    float bestDistance = 3.0e38;
    for (uint i = head; i != kBundleNil;) {
        BundleNode n = nodes.nodes[i];
        float distance = dir * (n.depth - d);
        float threshold = blBundleFacesBack(n.next, dir) ? frame.depthEpsilon : ownEpsilon;
        if (distance > threshold && distance < bestDistance) {
            best = i;
            bestDistance = distance;
        }
        i = n.next & kBundleIndexMask;
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

// Sorted lists (after the sort pass): the nearest fragment beyond depth d along dir * omega, with
// the same own-surface rule as blBundleNearest; forward queries stop at the first candidate.
uint blBundleSortedNearest(BundleNodes nodes, uint head, float d, float dir, float ownEpsilon, BundleFrame frame) {
    uint best = kBundleNil;
    for (uint i = head; i != kBundleNil;) {
        BundleNode n = nodes.nodes[i];
        float distance = dir * (n.depth - d);
        float threshold = blBundleFacesBack(n.next, dir) ? frame.depthEpsilon : ownEpsilon;
        if (distance > threshold) {
            best = i;
            if (dir > 0.0) {
                break; // ascending depths: the first one past the point is the nearest
            }
        } else if (dir < 0.0 && n.depth > d) {
            break; // backwards: everything from here on is behind the query
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
