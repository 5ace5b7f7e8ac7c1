// Light from the emitter points of this iteration (core/gpu/EmitterPointPass.h;
// shaders/shared/EmitterPoints.h has the estimator and the densities), reflected at x toward wo.
// Define BL_EMITTER_POINTS_SET and BL_EMITTER_POINTS_BINDING (the GpuEmitterPoint buffer) and
// include gpu/ShadowCubeLookup.glsl with BL_SHADOW_BINDING_2 = the points' cubes (map 1) first,
// or define BL_EMITTER_POINTS_MAP to the map that holds them (bidir: 2, BL_SHADOW_BINDING_3).
#ifndef BL_GPU_EMITTER_POINT_LIGHT_GLSL
#define BL_GPU_EMITTER_POINT_LIGHT_GLSL
#ifndef BL_EMITTER_POINTS_MAP
#define BL_EMITTER_POINTS_MAP 1u
#endif
#include "shared/Brdf.h"
#include "shared/EmitterPoints.h"

// One shadow tap per point (the receiver-plane test on the nearest texel, no PCF): the points
// change every iteration, so their average smooths the edges the filter would; and the 4x4
// filter's two-texel band beside concave contacts darkened the area-lit Cornell box's direct
// light by 0.6 % at 256^2 (raster, 2 seeds x 256 iterations: 0.9937 and 0.9938 of the reference),
// one tap by 0.12 % (0.9986, 0.9990), at 16x fewer shadow reads.
const int kEmitterPointTaps = 1;

layout(set = BL_EMITTER_POINTS_SET, binding = BL_EMITTER_POINTS_BINDING) readonly buffer BlEmitterPointBlock {
    GpuEmitterPointHeader blEmitterPointHeader;
    GpuEmitterPoint blEmitterPoints[];
};

// Point k seen from x: the point, the squared distance, the unit direction from the point to x
// and the cosine there; `lights` false where x lies behind the emitting face (or on the point) or
// not in front of the point's cube centre (lifted 1e-4 of the scene radius off the emitter): the
// cube renders only what lies in front of its centre (ShadowCubePass::frontTexels), and a receiver
// that close to the emitter's plane has cos_y below 1e-4 of the scene radius over its distance.
struct BlEmitterPointToward {
    GpuEmitterPoint p;
    float r2;
    vec3 fromPoint;
    float cosY;
    bool lights;
};

BlEmitterPointToward blEmitterPointToward(uint k, vec3 x) {
    BlEmitterPointToward t;
    t.p = blEmitterPoints[k];
    vec3 d = x - t.p.position;
    t.r2 = dot(d, d);
    t.fromPoint = t.r2 > 0.0 ? d * inversesqrt(t.r2) : vec3(0.0);
    t.cosY = dot(t.fromPoint, t.p.normal);
    t.lights = t.r2 > 0.0 && t.cosY > 0.0 && dot(x - t.p.cubeCentre, t.p.normal) > 0.0;
    return t;
}

// Multiple importance sampling (balance heuristic) against a strategy that reaches the same
// emitter point by a direction of solid-angle density directionPdf: the points' weight is
//   M p_A / (M p_A + directionPdf cos_y / r^2),
// and the other strategy's is the rest (blEmitterHitWeight). directionPdf = 0: the points alone.
// Folded into the estimate, L_e cos_x cos_y V / (r^2 M p_A) times that weight is
//   L_e cos_x cos_y V / (M p_A r^2 + directionPdf cos_y),
// which stays finite where either density vanishes.
// A strategy that reaches the same path from the emitter's side instead (bidir's area VPLs: the
// emitter point x0 drawn with p_A as the points are, with share P among the VPL sources, and x from
// it by a cosine-weighted direction) has the path density P p_A (cos_y / pi) cos_x / r^2 against
// the points' M p_A pOther, pOther the area density with which the caller's own strategy reached x:
// vplDensity = P / (pi pOther) adds vplDensity p_A cos_y cos_x to the denominator above (0: none).
// reflect = false: the irradiance at x instead (f = 1, m, albedo and wo unused), for a caller that
// applies its own reflectance (atlas texels: albedo / pi).
vec3 blEmitterPointsSum(vec3 x, vec3 n, GpuMaterial m, vec3 albedo, vec3 wo, float directionPdf, float vplDensity,
                        bool reflect) {
    uint count = blEmitterPointHeader.count;
    uint resolution = blEmitterPointHeader.resolution;
    vec3 radiance = vec3(0.0);
    for (uint k = 0u; k < count; ++k) {
        BlEmitterPointToward t = blEmitterPointToward(k, x);
        if (!t.lights) {
            continue;
        }
        vec3 wi = -t.fromPoint;
        float cosX = dot(n, wi);
        if (cosX <= 0.0) {
            continue; // lit from the side the camera does not see
        }
        float visibility =
            blShadowVisibilityTaps(BL_EMITTER_POINTS_MAP, kShadowCubeFaces * k, resolution, x - t.p.cubeCentre, n,
                                   kEmitterPointTaps);
        if (visibility <= 0.0) {
            continue;
        }
        vec3 f = reflect ? blEvalBrdf(m, albedo, n, wi, wo) : vec3(1.0);
        radiance += f * t.p.emission *
                    (cosX * t.cosY * visibility /
                     (float(count) * t.p.areaPdf * t.r2 + directionPdf * t.cosY +
                      vplDensity * t.p.areaPdf * t.cosY * cosX));
    }
    return radiance;
}

vec3 blEmitterPointsLight(vec3 x, vec3 n, GpuMaterial m, vec3 albedo, vec3 wo, float directionPdf) {
    return blEmitterPointsSum(x, n, m, albedo, wo, directionPdf, 0.0, true);
}

// The irradiance the points give x on each side of its surface (no MIS: the points alone). A
// point lights at most one side, the one its direction makes cos_x > 0 with, so each point needs
// one shadow lookup, made with that side's normal: the same terms blEmitterPointsSum(x, +-n, ...,
// reflect = false) adds for each side, at half the shadow reads and half the code (llvmpipe runs
// both sides of a branch, so a second call costs its full size).
void blEmitterPointsIrradianceBothSides(vec3 x, vec3 n, out vec3 front, out vec3 back) {
    front = vec3(0.0);
    back = vec3(0.0);
    uint count = blEmitterPointHeader.count;
    uint resolution = blEmitterPointHeader.resolution;
    for (uint k = 0u; k < count; ++k) {
        BlEmitterPointToward t = blEmitterPointToward(k, x);
        if (!t.lights) {
            continue;
        }
        float cosN = -dot(n, t.fromPoint);
        if (cosN == 0.0) {
            continue; // in x's plane
        }
        vec3 sideNormal = cosN > 0.0 ? n : -n;
        float cosX = abs(cosN);
        float visibility = blShadowVisibilityTaps(BL_EMITTER_POINTS_MAP, kShadowCubeFaces * k, resolution,
                                                  x - t.p.cubeCentre, sideNormal, kEmitterPointTaps);
        if (visibility <= 0.0) {
            continue;
        }
        vec3 light = t.p.emission * (cosX * t.cosY * visibility / (float(count) * t.p.areaPdf * t.r2));
        if (cosN > 0.0) {
            front += light;
        } else {
            back += light;
        }
    }
}

// The weight of the direction strategy where it meets an emitter of radiance `emission` at
// distance^2 r2 and cosine cosY, against this iteration's emitter points (the complement of the
// points' weight above; 1 without points, 0 where directionPdf = 0: the points alone).
float blEmitterHitWeight(vec3 emission, float directionPdf, float cosY, float r2) {
    uint count = blEmitterPointHeader.count;
    float points = float(count) * blEmitterAreaPdf(emission, blEmitterPointHeader.inversePower) * r2;
    float direction = directionPdf * cosY;
    return direction > 0.0 ? direction / (points + direction) : (count == 0u ? 1.0 : 0.0);
}

#endif
