// Light from this iteration's environment directions (core/bundle/EnvironmentShadowPass.h;
// shaders/shared/EnvironmentShadows.h has the estimator), at x on the side of n. Define
// BL_ENVIRONMENT_SHADOWS_SET, BL_ENVIRONMENT_SHADOWS_BINDING (the GpuEnvironmentShadow buffer) and
// BL_ENVIRONMENT_SHADOW_MAPS_BINDING (their depth maps, an rgba32f 2D array) first; a caller that
// also reaches the environment by escaping paths defines BL_ENVIRONMENT_SHADOW_RADIANCE(d), its own
// lookup of L_e(d), which its escapes read too (the MIS weights are then a partition of unity up to
// float rounding).
//
// Visibility is the depth maps' test (bundle/DepthMapVisibility.glsl): x's pixel centre, which
// box-filters the visibility over the pixel (the mean is kept except in strips half a pixel
// diagonal wide beside contact lines, where light is lost or gained), plus contact taps that keep
// a closed room's creases dark where the centre shows nothing near x. The map's surface counts from blBundleSurfaceEpsilon past both x's own
// plane and its facet's whatever its winding. That tolerance is partly a share of the map's pixel,
// so an occluder closer than it passes and light is gained there. Both fall with the pixel; the
// tests bound them by the strips' light either way. (On the stress suite's base-sky raster's
// direct light read +1.1 % / +0.35 % / +0.15 % at 128^2 / 512^2 / 2048^2 maps before the taps, sky
// leaking in at the wall creases; -0.56 % / -0.03 % / +0.07 % with them; +0.17 % / -0.04 % /
// -0.2 % with the facets' planes and the taps kept to points whose centre shows nothing near them,
// 64^2, 256 iterations of 32 directions, 8 at 2048^2.)
#ifndef BL_GPU_ENVIRONMENT_SHADOW_LIGHT_GLSL
#define BL_GPU_ENVIRONMENT_SHADOW_LIGHT_GLSL
#include "shared/Brdf.h"
#include "shared/EnvironmentShadows.h"
#include "shared/Sampling.h"

layout(set = BL_ENVIRONMENT_SHADOWS_SET, binding = BL_ENVIRONMENT_SHADOWS_BINDING) readonly buffer BlEnvironmentShadowBlock {
    GpuEnvironmentShadowHeader blEnvironmentShadowHeader;
    GpuEnvironmentShadow blEnvironmentShadows[];
};
layout(set = BL_ENVIRONMENT_SHADOWS_SET, binding = BL_ENVIRONMENT_SHADOW_MAPS_BINDING, rgba32f) uniform readonly image2DArray
    blEnvironmentShadowMaps;
#define BL_DEPTH_MAP_TEXEL(pixel, layer) imageLoad(blEnvironmentShadowMaps, ivec3(pixel, layer))
#include "bundle/DepthMapVisibility.glsl"

// Whether x (normal n of either sign, cosine = n . omega_k) sees the environment along direction k.
// A point outside the map's frame (which covers the scene's bounding sphere) has nothing in front.
bool blEnvironmentShadowVisible(uint k, vec3 x, vec3 n, float cosine) {
    BundleFrame frame = blEnvironmentShadows[k].frame;
    ivec2 pixel;
    float depth;
    if (!blBundlePixel(frame, x, pixel, depth)) {
        return true;
    }
    return !blDepthMapOccluded(frame, int(k), pixel, x, depth, n, cosine);
}

// The irradiance at x on both sides of its surface (normal n: `front`, -n: `back`) in one pass over
// the directions: each direction lights one side, one visibility test each (atlas texels).
void blEnvironmentShadowIrradianceBothSides(vec3 x, vec3 n, out vec3 front, out vec3 back) {
    front = vec3(0.0);
    back = vec3(0.0);
    for (uint k = 0u; k < blEnvironmentShadowHeader.count; ++k) {
        float cosine = dot(n, blEnvironmentShadows[k].frame.direction);
        if (cosine == 0.0 || !blEnvironmentShadowVisible(k, x, n, cosine)) {
            continue;
        }
        vec3 light = blEnvironmentShadows[k].weight * abs(cosine);
        if (cosine > 0.0) {
            front += light;
        } else {
            back += light;
        }
    }
}

// The balance heuristic against escaping paths along directions of solid-angle density
// directionPdf (shared/EnvironmentShadows.h: q~). The directions' K samples have the count-weighted
// density K q~(d); an escape along d with radiance L_e(d) takes the weight below, the rest goes to
// the directions. directionPdf = 0: the directions alone (escapes weigh 0 while the pass is on);
// pass off (requested = 0): escapes alone.
float blEnvironmentShadowDensity(vec3 radiance) {
    return blEnvironmentShadowHeader.luminanceScale * blLuminance(radiance) + blEnvironmentShadowHeader.uniformDensity;
}

float blEnvironmentEscapeWeight(vec3 radiance, float directionPdf) {
    uint requested = blEnvironmentShadowHeader.requested;
    if (requested == 0u) {
        return 1.0;
    }
    float directions = float(requested) * blEnvironmentShadowDensity(radiance);
    return directionPdf > 0.0 ? directionPdf / (directionPdf + directions) : 0.0;
}

// The light the directions reflect at x toward wo, sum_k f(x, omega_k, wo) weight_k V_k (n . omega_k),
// each weighted K q~ / (K q~ + directionPdf) against escapes where the caller has them
// (directionPdf > 0, BL_ENVIRONMENT_SHADOW_RADIANCE defined); directionPdf = 0: the directions alone.
vec3 blEnvironmentShadowLight(vec3 x, vec3 n, GpuMaterial m, vec3 albedo, vec3 wo, float directionPdf) {
    vec3 sum = vec3(0.0);
    float requested = float(blEnvironmentShadowHeader.requested);
    for (uint k = 0u; k < blEnvironmentShadowHeader.count; ++k) {
        vec3 omega = blEnvironmentShadows[k].frame.direction;
        float cosine = dot(n, omega);
        if (cosine <= 0.0 || !blEnvironmentShadowVisible(k, x, n, cosine)) {
            continue;
        }
        float weight = 1.0;
#ifdef BL_ENVIRONMENT_SHADOW_RADIANCE
        if (directionPdf > 0.0) {
            float directions = requested * blEnvironmentShadowDensity(BL_ENVIRONMENT_SHADOW_RADIANCE(omega));
            weight = directions / (directions + directionPdf);
        }
#endif
        sum += blEvalBrdf(m, albedo, n, omega, wo) * blEnvironmentShadows[k].weight * (cosine * weight);
    }
    return sum;
}

#endif
