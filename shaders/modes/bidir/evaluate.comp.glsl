#version 460
#extension GL_GOOGLE_include_directive : require
// Mode bidir, evaluation at every camera-visible point x3 = x (normal n turned toward the camera)
// of K VPL/bundle pairs ([TO12] Eq. 3-6, EQUATIONS.md section 2). Pair k contributes one-bounce
// paths x0 -> x_j -> x by two strategies:
//   j = 1 (VPL): x_j = y_k, the VPL (host-sampled light ray, area density p_A1(y) =
//     P(l) p_e (n_y . w_{y,0}) / |y - x0|^2), visibility y - x from the VPL's shadow cube;
//   j = 2 (bundle): x_j = the first surface along d = +-omega_k from x in bundle k (area density
//     p_A2(y) = p_r (n_y . w_{y,x}) / |y - x|^2), lit by every light through its shadow cube.
// Each term is I f_{0,j,x} f_{j,x,4} G / p_A with the path's geometry, and MIS weighs it by
// p_A,j / (p_A1 + p_A2) (balance heuristic): the ratio equals EQUATIONS.md's p1/p2, both densities
// of the same vertex in the same (area) measure. The mean over the K pairs is one sample of the
// indirect1 layer; direct light comes from the lights' shadow cubes as in `raster`.
#include "modes/bidir/BidirShared.h"
#include "bundle/Traversal.glsl"
#include "shared/Brdf.h"
#include "shared/Lights.h"
#include "shared/Octahedral.h"
#define BL_ACCUM_LAYERS kBidirAccumLayers
#include "gpu/CameraSet.glsl"
#define BL_SHADOW_SET kBidirSet
#define BL_SHADOW_BINDING kBidirBindingShadowMaps
#define BL_SHADOW_BINDING_2 kBidirBindingVplMaps
#include "gpu/ShadowCubeLookup.glsl"

layout(local_size_x = kBidirGroupSize, local_size_y = kBidirGroupSize) in;

layout(set = kBidirSet, binding = kBidirBindingLights) readonly buffer LightBlock { GpuLight lights[]; };
layout(set = kBidirSet, binding = kBidirBindingVpls) readonly buffer VplBlock { BidirVpl vpls[]; };
layout(push_constant) uniform PushBlock { BidirPush push; };

const uint kBidirMapVpl = 1u; // blShadowVisibilityIn's map 1: the VPLs' cubes (map 0: the lights')

// Light l's direct light reflected at point p (normal n turned toward wo) toward wo, by its shadow
// cube; with the light ray's solid-angle density P(l) p_e and geometry when asked (MIS).
vec3 lightAt(uint l, vec3 p, vec3 n, GpuMaterial m, vec3 albedo, vec3 wo, out float areaPdf) {
    areaPdf = 0.0;
    GpuLight light = lights[l];
    vec3 d = p - light.position;
    float r2 = dot(d, d);
    if (!(r2 > 0.0)) {
        return vec3(0.0);
    }
    vec3 fromLight = d * inversesqrt(r2);
    vec3 wi = -fromLight;
    float cosine = dot(n, wi);
    float profile = blLightProfile(light, fromLight);
    if (cosine <= 0.0 || profile <= 0.0) {
        return vec3(0.0); // lit on the side wo does not see, or outside the spot cone
    }
    areaPdf = push.lightSelectPdf * blBidirEmissionPdf(light, fromLight) * cosine / r2;
    float visibility = blShadowVisibility(kShadowCubeFaces * l, push.shadowResolution, d, n);
    if (visibility <= 0.0) {
        return vec3(0.0);
    }
    return blEvalBrdf(m, albedo, n, wi, wo) * light.intensity * (profile * visibility * cosine / r2);
}

// Strategy j = 1 of pair k at x.
vec3 vplTerm(uint k, vec3 x, vec3 n, GpuMaterial m, vec3 albedo, vec3 wo) {
    BidirVpl v = vpls[k];
    if (v.valid == 0u) {
        return vec3(0.0);
    }
    vec3 toVpl = v.position - x;
    float r2 = dot(toVpl, toVpl);
    if (!(r2 > 0.0)) {
        return vec3(0.0);
    }
    vec3 wi = toVpl * inversesqrt(r2);
    float cosX = dot(n, wi);
    float cosY = -dot(v.normal, wi); // x must lie on the VPL's lit side: reflection, not transmission
    if (cosX <= 0.0 || cosY <= 0.0) {
        return vec3(0.0);
    }
    float visibility = blShadowVisibilityIn(kBidirMapVpl, kShadowCubeFaces * k, push.vplResolution, x - v.cubeCentre, n);
    if (visibility <= 0.0) {
        return vec3(0.0);
    }
    vec3 fy = blEvalBrdf(materials[v.material], v.albedo, v.normal, v.toLight, -wi);
    vec3 fx = blEvalBrdf(m, albedo, n, wi, wo);
    // I f_y f_x G(y, x) / (P(l) p_e): the light ray's own cos/r^2 cancels against its area pdf.
    vec3 estimate = v.intensity * fy * fx * (visibility * cosX * cosY / (r2 * v.pdfLight));
    if (push.strategy == kBidirStrategyVpl) {
        return estimate;
    }
    float p2 = push.hemispherePdf * cosY / r2; // the bundle strategy's area density of y
    return estimate * (v.areaPdf / (v.areaPdf + p2));
}

// Strategy j = 2 of pair k at x.
vec3 bundleTerm(uint k, vec3 x, vec3 n, GpuMaterial m, vec3 albedo, vec3 wo) {
    BundleFrame frame = blBundlePoolFrame(push.pool, k);
    float cosine = dot(n, frame.direction);
    float side = cosine >= 0.0 ? 1.0 : -1.0;
    vec3 d = side * frame.direction;
    ivec2 bundlePixel;
    float depth;
    if (!blBundlePixel(frame, x, bundlePixel, depth)) {
        return vec3(0.0); // the frame covers the scene's bounding sphere: never for scene points
    }
    BundleNodes nodes = BundleNodes(push.pool.nodes);
    uint head = blBundleHead(blBundlePoolHeads(push.pool, k), frame, bundlePixel);
    uint hit = blBundleNearest(nodes, head, depth, side, blBundleOwnSurfaceEpsilon(frame, cosine), frame);
    if (hit == kBundleNil) {
        return vec3(0.0); // escapes: environment light is not bidir's one-bounce term
    }
    BundleHit payload = BundleHitPayload(push.pool.payload).hits[hit];
    // y on the bundle pixel's centre ray, up to half a pixel beside x's exact ray (the bundle
    // resolution's bias, shrinking with the pixel size).
    vec3 y = frame.origin + (float(bundlePixel.x) + 0.5) * frame.pixelSize * frame.axisX +
             (float(bundlePixel.y) + 0.5) * frame.pixelSize * frame.axisY + nodes.nodes[hit].depth * frame.direction;
    vec3 toX = x - y;
    float r2 = dot(toX, toX);
    if (!(r2 > 0.0)) {
        return vec3(0.0);
    }
    vec3 wy = toX * inversesqrt(r2);
    vec3 shading = blUnpackOctahedral(payload.normal);
    vec3 ny = dot(shading, wy) >= 0.0 ? shading : -shading; // two-sided reflection
    float cosY = dot(ny, wy);
    GpuMaterial my = materials[payload.material & kBundleHitMaterialMask];
    vec3 fx = blEvalBrdf(m, albedo, n, d, wo) * (abs(cosine) / push.hemispherePdf);
    float p2 = push.hemispherePdf * max(cosY, 0.0) / r2;
    vec3 sum = vec3(0.0);
    for (uint l = 0u; l < push.lightCount; ++l) {
        float p1;
        // Textured albedo at y: not yet (the material's albedo; BidirMode.h says so).
        vec3 reflected = lightAt(l, y, ny, my, my.albedo, wy, p1);
        float weight = push.strategy == kBidirStrategyBundle ? 1.0 : (p2 > 0.0 ? p2 / (p1 + p2) : 0.0);
        sum += reflected * weight;
    }
    return sum * fx;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) {
        return;
    }
    // The pool contract: a build that ran out of nodes left lists incomplete; the mode grows the
    // pool and redoes the frame, so nothing of this one may be added.
    if (push.strategy != kBidirStrategyVpl && blBundlePoolOverflowed(BundleCounterBlock(push.pool.counters))) {
        return;
    }
    if (!blCameraHitSurface(pixel)) {
        blAccumulateLayer(pixel, kPathEmitted, blCameraBackground(pixel, push.samplePosition,
                                                                  push.environmentPresent != 0u,
                                                                  push.environmentRotation));
        return;
    }
    vec3 layers[kPathLayerCount];
    for (uint l = 0u; l < kPathLayerCount; ++l) {
        layers[l] = vec3(0.0);
    }
    vec3 x = imageLoad(gbuffer[kGBufferPosition], pixel).xyz;
    vec4 normalMaterial = imageLoad(gbuffer[kGBufferNormal], pixel);
    vec3 n = normalMaterial.xyz;
    GpuMaterial m = materials[uint(normalMaterial.w)];
    vec3 albedo = imageLoad(gbuffer[kGBufferAlbedo], pixel).rgb;
    vec3 wo = normalize(camera.position - x);
    layers[kPathEmitted] = imageLoad(gbuffer[kGBufferEmission], pixel).rgb;
    for (uint l = 0u; l < push.lightCount; ++l) {
        float unused;
        layers[kPathDirect] += lightAt(l, x, n, m, albedo, wo, unused);
    }
    vec3 indirect = vec3(0.0);
    for (uint k = 0u; k < push.pairs; ++k) {
        if (push.strategy != kBidirStrategyBundle) {
            indirect += vplTerm(k, x, n, m, albedo, wo);
        }
        if (push.strategy != kBidirStrategyVpl) {
            indirect += bundleTerm(k, x, n, m, albedo, wo);
        }
    }
    layers[kPathIndirect1] = indirect / float(max(push.pairs, 1u));
    blAccumulate(pixel, layers);
}
