#version 460
#extension GL_GOOGLE_include_directive : require
// Mode multibounce, imperfect bundles ([TO12p]): the point sets of one iteration. Point i of
// direction k (global index k * pointsPerDirection + i) is uniform by area over all surfaces: a
// triangle from the area CDF (binary search), then a uniform point in it (square-root
// barycentrics). Each direction's points come from their own random numbers, so every bundle
// sees a different point set. The point becomes a BundleSplat (disc of push.radius in the
// triangle's plane, oriented like the triangle's front face so the bundle's face bit matches a
// triangle build) and a MultibouncePoint (shading normal, triangle for emission, the UV at the point
// and its gradient in world space: the poster's texture coordinates at each splat corner, as one
// linear function; the path pass looks textures up where a path meets the splat).
#include "modes/multibounce/MultibounceShared.h"
#include "modes/multibounce/DrawSearch.glsl"
#include "shared/GpuTypes.h"
#include "shared/Octahedral.h"
#include "shared/Random.h"

layout(local_size_x = kMultibouncePointsGroupSize) in;

layout(set = 0, binding = kMultibouncePointsBindingCdf) readonly buffer CdfBlock { float cdf[]; };
layout(set = 0, binding = kMultibouncePointsBindingDraws) readonly buffer DrawBlock { MultibounceDraw draws[]; };
layout(set = 0, binding = kMultibouncePointsBindingVertices) readonly buffer VertexBlock { GpuVertex vertices[]; };
layout(set = 0, binding = kMultibouncePointsBindingIndices) readonly buffer IndexBlock { uint indices[]; };
layout(set = 0, binding = kMultibouncePointsBindingPlanes) readonly buffer PlaneBlock { vec4 planes[]; };
layout(set = 0, binding = kMultibouncePointsBindingSplats) writeonly buffer SplatBlock { BundleSplat splats[]; };
layout(set = 0, binding = kMultibouncePointsBindingPoints) writeonly buffer PointBlock { MultibouncePoint points[]; };
layout(push_constant) uniform PushBlock { MultibouncePointsPush push; };

// The first triangle whose inclusive CDF exceeds u (triangles of zero area are never chosen).
uint triangleOf(float u) {
    uint lo = 0u, hi = push.triangleCount - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (cdf[mid] > u) {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}

BL_DEFINE_DRAW_SEARCH(drawOf, draws) // the draw holding a triangle

// Gradient in the plane of the triangle (edges e1, e2 from corner 0) of the linear function that
// grows by f1 along e1 and f2 along e2; zero for a degenerate triangle.
vec3 planeGradient(vec3 e1, vec3 e2, float f1, float f2) {
    float a11 = dot(e1, e1), a12 = dot(e1, e2), a22 = dot(e2, e2);
    float det = a11 * a22 - a12 * a12;
    if (!(det > 1e-30 * a11 * a22)) {
        return vec3(0.0);
    }
    return ((a22 * f1 - a12 * f2) * e1 + (a11 * f2 - a12 * f1) * e2) / det;
}

void main() {
    uint index = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * kMultibouncePointsGroupSize) + gl_GlobalInvocationID.x;
    if (index >= push.count) {
        return;
    }
    uint direction = index / push.pointsPerDirection;
    uint local = index - direction * push.pointsPerDirection;
    // Stream per (iteration, direction), sample = point: the first pairs stratify a direction's
    // points over the CDF and within triangles.
    RandomStream rng = blRandomStream(push.seed ^ blHash(push.iteration), direction, local);
    vec2 u = blRandom2(rng);
    vec2 v = blRandom2(rng);
    uint t = triangleOf(u.x * cdf[push.triangleCount - 1u]);
    MultibounceDraw d = draws[drawOf(t, push.drawCount)];
    uint first = 3u * t;
    GpuVertex v0 = vertices[indices[first] + d.vertexOffset];
    GpuVertex v1 = vertices[indices[first + 1u] + d.vertexOffset];
    GpuVertex v2 = vertices[indices[first + 2u] + d.vertexOffset];
    float s = sqrt(v.x);
    float b1 = s * (1.0 - v.y), b2 = s * v.y, b0 = 1.0 - b1 - b2;
    vec3 local3 = b0 * v0.positionU.xyz + b1 * v1.positionU.xyz + b2 * v2.positionU.xyz;
    mat3 rotation = mat3(d.model);
    vec3 geometric = rotation * planes[t].xyz;
    vec3 shading = rotation * (b0 * v0.normalV.xyz + b1 * v1.normalV.xyz + b2 * v2.normalV.xyz);
    float shadingLength = length(shading);
    shading = shadingLength > 1e-20 ? shading / shadingLength : geometric;

    BundleSplat splat;
    splat.position = (d.model * vec4(local3, 1.0)).xyz;
    // A triangle with no plane (zero area) is never chosen; if rounding chose one, the splat
    // builder refuses its zero normal and draws nothing.
    splat.radius = push.radius;
    splat.normal = geometric;
    splat.material = d.material;
    splats[index] = splat;

    MultibouncePoint p;
    p.normal = blPackOctahedral(dot(shading, shading) > 0.0 ? shading : vec3(0.0, 0.0, 1.0));
    p.triangle = t;
    p.uv = vec2(0.0);
    p.gradientA = 0u;
    p.gradientB = 0u;
    p.gradientC = 0u;
    p.pad0 = 0u;
    if (push.textured != 0u) {
        vec2 uv0 = vec2(v0.positionU.w, v0.normalV.w), uv1 = vec2(v1.positionU.w, v1.normalV.w),
             uv2 = vec2(v2.positionU.w, v2.normalV.w);
        p.uv = b0 * uv0 + b1 * uv1 + b2 * uv2;
        // World-space edges (the draw's transform at the bundles' time).
        vec3 e1 = rotation * (v1.positionU.xyz - v0.positionU.xyz);
        vec3 e2 = rotation * (v2.positionU.xyz - v0.positionU.xyz);
        vec3 gu = planeGradient(e1, e2, uv1.x - uv0.x, uv2.x - uv0.x);
        vec3 gv = planeGradient(e1, e2, uv1.y - uv0.y, uv2.y - uv0.y);
        p.gradientA = packHalf2x16(gu.xy);
        p.gradientB = packHalf2x16(vec2(gu.z, gv.x));
        p.gradientC = packHalf2x16(gv.yz);
    }
    points[index] = p;
}
