#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Compute bundle build (bundle_backend = compute): software rasterization of one draw's triangles,
// one invocation per triangle. The same nodes as the rasterized exact build (PoolAppend.glsl with
// BL_EXACT_DEPTH): vertices snapped to the subpixel grid where the rasterizer places them
// (Projection.glsl), pixel centres tested with exact 64-bit edge functions and a top-left rule
// (a centre on an edge shared by two triangles goes to exactly one), depth and face from the
// triangle's plane along the pixel's ray, the allocator's overflow contract and the list link
// from PoolNodes.glsl, and the same hit payload (PoolHit.glsl) where the pool has one.
//
// Each row of a triangle's box is walked only over its covered span, found exactly from the three
// edge functions (integer floor division, the same inequalities as the per-pixel test), so the
// cost is rows + fragments, not the box's area (long thin triangles in Sponza); a row's nodes are
// allocated with one atomic (blPoolAllocate), not one per fragment.
//
// No invocation loops more than kBundleComputeBandPixels times: the small pass walks each triangle
// whose box is at most that large and lists the others, the big pass (an indirect dispatch) walks
// each listed triangle in bands of push.rowsPerBand tile rows. (lavapipe's shader compiler ends
// any loop after 65535 iterations, counting a nested loop's iterations over all passes of the
// outer one: a triangle walked whole lost its fragments beyond that, 20% of them in Sponza at
// 1024^2.)
#include "bundle/ComputeBuildShared.h"
#include "bundle/PoolHit.glsl"
#include "bundle/PoolNodes.glsl"
#include "bundle/Projection.glsl"
#include "shared/GpuTypes.h"

layout(local_size_x = kBundleComputeGroupSize) in;
layout(push_constant) uniform PushBlock { BundleComputePush push; };
layout(set = 0, binding = 0) readonly buffer PlaneBlock { vec4 planes[]; };
layout(set = 0, binding = 1) readonly buffer VertexBlock { GpuVertex vertices[]; };
layout(set = 0, binding = 2) readonly buffer IndexBlock { uint indices[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer BigList {
    BundleComputeBigHeader header;
    uint triangles[];
};

// Subpixel units: 1 / kBundleSubpixelGrid of a pixel.
const int64_t kUnit = int64_t(kBundleSubpixelGrid);

// Edge a -> b owns the centres exactly on it when it is a "top" or "left" edge of a
// counter-clockwise triangle: of the two directions of a shared edge exactly one does.
bool ownsCentresOnEdge(i64vec2 a, i64vec2 b) {
    i64vec2 e = b - a;
    return e.y < 0 || (e.y == 0 && e.x > 0);
}

int64_t edgeFunction(i64vec2 a, i64vec2 b, i64vec2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }

// floor(a / b) for b > 0 (GLSL's integer division truncates toward zero).
int64_t floorDivide(int64_t a, int64_t b) {
    int64_t q = a / b;
    return q * b > a ? q - 1 : q;
}

// Narrows [first, last] to the pixels x of the row whose centres (x * kUnit + half, centreY) edge
// a -> b covers: edgeFunction >= 1, or >= 0 where the edge owns centres on it. Along a row the edge
// function is C - D x with D = (b.y - a.y) kUnit, so the condition bounds x from one side.
void clipSpanToEdge(i64vec2 a, i64vec2 b, bool owns, int64_t centreY, int64_t half_, inout int64_t first, inout int64_t last) {
    int64_t threshold = owns ? 0 : 1;
    int64_t d = (b.y - a.y) * kUnit;
    int64_t c = (b.x - a.x) * (centreY - a.y) - (b.y - a.y) * (half_ - a.x) - threshold; // covered: c - d x >= 0
    if (d == 0) {
        if (c < 0) {
            last = first - 1;
        }
    } else if (d > 0) {
        last = min(last, floorDivide(c, d));
    } else {
        first = max(first, -floorDivide(c, -d)); // x >= ceil(c / d) = -floor(c / -d)
    }
}

void main() {
    const bool bigPass = push.pass == kBundleComputeBigPass;
    BigList big = BigList(push.bigAddress);
    uint local = bigPass ? big.triangles[gl_GlobalInvocationID.y] : gl_GlobalInvocationID.x;
    if (local >= push.triangleCount || (bigPass && gl_GlobalInvocationID.x >= push.bands)) {
        return;
    }
    // The rows stored as columns: a point's image is vec4(p, 1) * modelRows.
    mat4 model = transpose(mat4(push.modelRows[0], push.modelRows[1], push.modelRows[2], vec4(0.0, 0.0, 0.0, 1.0)));
    BundleFrame frame = BundleFrames(push.frameAddress).frames[0];
    BundleCounterBlock block = BundleCounterBlock(push.counterAddress);
    uint triangle = push.firstPrimitive + local;
    i64vec2 v[3];
    GpuVertex corners[3];
    for (uint k = 0u; k < 3u; ++k) {
        corners[k] = vertices[indices[3u * triangle + k] + push.vertexOffset];
        float depthIgnored;
        vec2 snapped = blBundleSnappedGrid(frame, (model * vec4(corners[k].positionU.xyz, 1.0)).xyz, depthIgnored);
        if (any(isnan(snapped)) || any(isinf(snapped)) || any(greaterThan(abs(snapped), vec2(1.0e9)))) {
            return; // a vertex the rasterizer would clip away entirely or cannot place
        }
        v[k] = i64vec2(snapped * kBundleSubpixelGrid); // exact: snapped is a multiple of 1/grid
    }
    int64_t area = edgeFunction(v[0], v[1], v[2]);
    if (area == 0) {
        return; // no pixel centre lies strictly inside a degenerate projection
    }
    if (area < 0) {
        i64vec2 t = v[1];
        v[1] = v[2];
        v[2] = t;
    }
    vec4 plane = planes[triangle];
    vec3 n = mat3(model) * plane.xyz;
    float offset = plane.w + dot(n, model[3].xyz);
    if (dot(n, n) == 0.0) {
        return; // GpuScene's kNoPlane: collinear or non-finite corners, nothing to hit
    }
    const bool payload = push.payloadAddress != uvec2(0u);
    BlPoolTriangle hitCorners;
    if (payload) {
        hitCorners = blPoolTriangle(corners[0], corners[1], corners[2], model, n, -frame.direction, push.material,
                                    triangle);
    }
    // Pixels of the tile whose centres (x + 1/2, y + 1/2 in the whole grid) lie in the bounding box.
    i64vec2 lo = min(v[0], min(v[1], v[2])), hi = max(v[0], max(v[1], v[2]));
    int64_t half_ = kUnit / 2;
    int x0 = int(max((lo.x - half_ + kUnit - 1) / kUnit, int64_t(frame.tileX)));
    int y0 = int(max((lo.y - half_ + kUnit - 1) / kUnit, int64_t(frame.tileY)));
    int x1 = int(min((hi.x - half_) / kUnit, int64_t(frame.tileX + frame.width) - 1));
    int y1 = int(min((hi.y - half_) / kUnit, int64_t(frame.tileY + frame.height) - 1));
    // Negative numerators round toward zero above; centres below 0 are outside every tile anyway.
    x0 = max(x0, int(frame.tileX));
    y0 = max(y0, int(frame.tileY));
    if (bigPass) {
        int bandFirst = int(frame.tileY) + int(gl_GlobalInvocationID.x * push.rowsPerBand);
        y0 = max(y0, bandFirst);
        y1 = min(y1, bandFirst + int(push.rowsPerBand) - 1);
    } else if (x1 >= x0 && y1 >= y0 && uint(x1 - x0 + 1) * uint(y1 - y0 + 1) > kBundleComputeBandPixels) {
        big.triangles[atomicAdd(big.header.dispatchY, 1u)] = local;
        return;
    }
    uint capacity = block.counters.capacity;
    bool own0 = ownsCentresOnEdge(v[1], v[2]), own1 = ownsCentresOnEdge(v[2], v[0]), own2 = ownsCentresOnEdge(v[0], v[1]);
    for (int y = y0; y <= y1; ++y) {
        int64_t centreY = int64_t(y) * kUnit + half_, first = x0, last = x1;
        clipSpanToEdge(v[1], v[2], own0, centreY, half_, first, last);
        clipSpanToEdge(v[2], v[0], own1, centreY, half_, first, last);
        clipSpanToEdge(v[0], v[1], own2, centreY, half_, first, last);
        if (first > last) {
            continue; // (the bounds may lie far outside the box here: never cast them)
        }
        int row = y - int(frame.tileY);
        // Two walks of the span: count the fragments inside the depth range, allocate them at once,
        // then link them (the same float depth both times).
        uint count = 0u;
        for (int x = int(first); x <= int(last); ++x) {
            float depth;
            bool front;
            count += blPoolPlaneDepth(frame, blBundlePixelRay(frame, vec2(x - int(frame.tileX), row) + 0.5), n, offset, depth, front) &&
                     depth >= frame.depthNear && depth <= frame.depthFar ? 1u : 0u;
        }
        uint index = count == 0u ? kBundleNil : blPoolAllocate(block, count);
        if (index == kBundleNil) {
            continue;
        }
        // Never past the row's own nodes, whatever the second depth evaluation says.
        uint end = min(index + count, capacity);
        for (int x = int(first); x <= int(last) && index < end; ++x) {
            int column = x - int(frame.tileX);
            float depth;
            bool front;
            vec3 ray = blBundlePixelRay(frame, vec2(column, row) + 0.5);
            if (blPoolPlaneDepth(frame, ray, n, offset, depth, front) && depth >= frame.depthNear &&
                depth <= frame.depthFar) {
                blPoolLink(push.headAddress, push.nodeAddress, uint(row) * frame.width + uint(column), index, depth, front);
                if (payload) {
                    BundleHitPayload(push.payloadAddress).hits[index] = blPoolTriangleHit(hitCorners, ray + depth * frame.direction);
                }
                ++index;
            }
        }
    }
}
