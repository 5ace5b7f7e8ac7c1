// The hit payload of a triangle's fragments (BundleTypes.h: BundleHit), shared by both build
// backends so that a mode reads the same hits whichever built its bundles: the rasterized exact
// build (PoolAppend.glsl) gathers the triangle for each fragment, the compute build
// (compute_triangles.comp.glsl) once per triangle and reuses it along its spans.
#ifndef BL_BUNDLE_POOL_HIT_GLSL
#define BL_BUNDLE_POOL_HIT_GLSL
#include "shared/BundleTypes.h"
#include "shared/GpuTypes.h"
#include "shared/Barycentrics.h"
#include "shared/Octahedral.h"

// A unit vector along v, or `fallback` when v cancelled to (nearly) zero: normalize(0) is NaN.
vec3 blPoolSafeNormalize(vec3 v, vec3 fallback) {
    float lengthSquared = dot(v, v);
    return lengthSquared > 1e-30 ? v * inversesqrt(lengthSquared) : fallback;
}

// A triangle in world space (its mesh's rigid transform applied) with what its hits carry.
struct BlPoolTriangle {
    vec3 p0;        // corner 0
    vec3 e1;        // corner 1 - corner 0
    vec3 e2;        // corner 2 - corner 0
    vec3 n0;        // shading normals at the corners, rotated (not normalized)
    vec3 n1;
    vec3 n2;
    vec2 uv0;
    vec2 uv1;
    vec2 uv2;
    vec3 facet;     // unit normal of the triangle's plane
    uint material;  // low 24 bits
    uint id;        // global triangle index
};

// `facet`: the triangle's plane normal in world space, or `fallback` where it has none (GpuScene
// gives degenerate triangles a zero normal).
BlPoolTriangle blPoolTriangle(GpuVertex v0, GpuVertex v1, GpuVertex v2, mat4 model, vec3 facet, vec3 fallback,
                              uint material, uint id) {
    mat3 rotation = mat3(model);
    BlPoolTriangle t;
    t.p0 = (model * vec4(v0.positionU.xyz, 1.0)).xyz;
    t.e1 = rotation * (v1.positionU.xyz - v0.positionU.xyz);
    t.e2 = rotation * (v2.positionU.xyz - v0.positionU.xyz);
    t.n0 = rotation * v0.normalV.xyz;
    t.n1 = rotation * v1.normalV.xyz;
    t.n2 = rotation * v2.normalV.xyz;
    t.uv0 = vec2(v0.positionU.w, v0.normalV.w);
    t.uv1 = vec2(v1.positionU.w, v1.normalV.w);
    t.uv2 = vec2(v2.positionU.w, v2.normalV.w);
    t.facet = blPoolSafeNormalize(facet, fallback);
    t.material = material & kBundleHitMaterialMask;
    t.id = id;
    return t;
}

// The hit of triangle t's fragment whose ray meets its plane at `point`.
BundleHit blPoolTriangleHit(BlPoolTriangle t, vec3 point) {
    vec2 b = blTriangleBarycentrics(point - t.p0, t.e1, t.e2);
    float b0 = 1.0 - b.x - b.y;
    BundleHit hit;
    hit.normal = blPackOctahedral(blPoolSafeNormalize(b0 * t.n0 + b.x * t.n1 + b.y * t.n2, t.facet));
    hit.plane = blPackOctahedral(t.facet);
    hit.material = t.material;
    hit.uv = b0 * t.uv0 + b.x * t.uv1 + b.y * t.uv2;
    hit.id = t.id;
    hit.barycentric = packUnorm2x16(b);
    hit.pad = 0u;
    return hit;
}
#endif
