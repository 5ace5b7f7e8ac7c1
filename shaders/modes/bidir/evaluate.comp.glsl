#version 460
#extension GL_GOOGLE_include_directive : require
// Mode bidir, evaluation at every camera-visible point x3 = x (normal n turned toward the camera)
// of K VPL/bundle pairs ([TO12 Eq. 3]-[TO12 Eq. 6], papers/EQUATIONS.md). Pair k contributes one-bounce
// paths x0 -> x_j -> x by two strategies:
//   j = 1 (VPL): x_j = y_k, the VPL (host-sampled light ray, area density p_A1(y) =
//     P(l) p_e (n_y . w_{y,0}) / |y - x0|^2), visibility y - x from the VPL's shadow cube;
//   j = 2 (bundle): x_j = the first surface along d = +-omega_k from x in bundle k (area density
//     p_A2(y) = p_r (n_y . w_{y,x}) / |y - x|^2), lit by every light through its shadow cube.
// Each term is I f_{0,j,x} f_{j,x,4} G / p_A with the path's geometry, and MIS weighs it by
// p_A,j / (p_A1 + p_A2) (balance heuristic): the ratio equals p1/p2 of [TO12 Eq. 6], both densities
// of the same vertex in the same (area) measure. Area emitters: the VPLs of the area source (x0 by
// power, VplSampler.h) against the M emitter points at the bundle's hit, by the balance heuristic
// with counts, p_A1 / (p_A1 + M p_A2) (x0's own density p_A is the same in both). The mean over the K pairs is one sample of the
// indirect1 layer; direct light comes from the lights' shadow cubes as in `raster`. With
// bounces = 2 pair k also gives the two-bounce path x0 -> VPL k -> bundle k's hit -> x (Eq. 7-8,
// one strategy, no MIS), the mean over the pairs one sample of the indirect2 layer.
#include "modes/bidir/BidirShared.h"
#include "modes/bidir/EvaluateSpecialization.h"
#include "modes/bidir/Interleave.h"
#include "bundle/Traversal.glsl"
#include "shared/Brdf.h"
#include "shared/Lights.h"
#include "shared/Octahedral.h"
#include "modes/bidir/Suppression.h"
#include "modes/bidir/RsmPdf.glsl"
#define BL_ACCUM_LAYERS kBidirAccumLayers
#include "gpu/CameraSet.glsl"
#define BL_SHADOW_SET kBidirSet
#define BL_SHADOW_BINDING kBidirBindingShadowMaps
#define BL_SHADOW_BINDING_2 kBidirBindingVplMaps
#define BL_SHADOW_BINDING_3 kBidirBindingEmitterShadowMaps
#include "gpu/ShadowCubeLookup.glsl"
#define BL_EMITTER_POINTS_SET kBidirSet
#define BL_EMITTER_POINTS_BINDING kBidirBindingEmitterPoints
#define BL_EMITTER_POINTS_MAP 2u
#include "gpu/EmitterPointLight.glsl"

layout(local_size_x = kBidirGroupSize, local_size_y = kBidirGroupSize) in;

// EvaluateSpecialization.h: fixed per pipeline, so the paths they rule out are compiled away.
layout(constant_id = kBidirSpecStrategy) const uint kStrategy = kBidirStrategyMis;
layout(constant_id = kBidirSpecBounces) const uint kBounces = 2u;
layout(constant_id = kBidirSpecSuppression) const uint kSuppression = kBidirSuppressionNone;
layout(constant_id = kBidirSpecGlossy) const bool kGlossy = true;
layout(constant_id = kBidirSpecTextured) const bool kTextured = true;
layout(constant_id = kBidirSpecEnvironment) const bool kEnvironment = true;
layout(constant_id = kBidirSpecRsm) const bool kRsm = true;
layout(constant_id = kBidirSpecVplTaps) const int kVplTaps = 4;
layout(constant_id = kBidirSpecAreaVpls) const bool kAreaVpls = false;

layout(set = kBidirSet, binding = kBidirBindingLights) readonly buffer LightBlock { GpuLight lights[]; };
layout(set = kBidirSet, binding = kBidirBindingVpls) readonly buffer VplBlock { BidirVpl vpls[]; };
layout(push_constant) uniform PushBlock { BidirPush push; };
layout(set = kBidirSet, binding = kBidirBindingFrame, rgba32f) uniform writeonly image2DArray interleaveFrame;
layout(set = kBidirSet, binding = kBidirBindingInterleave) readonly buffer InterleaveBlock { InterleaveEvaluate interleave; };

// The pixel's sample: accumulated here, or with interleaving written to the frame image for the
// blur / temporal pass (shaders/modes/bidir/interleave.comp.glsl), which accumulates it.
void emitSample(ivec2 pixel, vec3 layers[kPathLayerCount]) {
    if (interleave.deferred == 0u) {
        blAccumulate(pixel, layers);
        return;
    }
    for (uint l = 0u; l < kPathLayerCount; ++l) {
        imageStore(interleaveFrame, ivec3(pixel, int(l)), vec4(layers[l], kFrameWritten));
    }
}

const uint kBidirMapVpl = 1u; // blShadowVisibilityIn's map 1: the VPLs' cubes (map 0: the lights')
// Set when x fell outside a bundle's frame: the pixel's sample is dropped (never added, counted by
// the accumulator as dropped_samples) rather than biased by a missing bundle term.
bool gOutsideBundle = false;
// The camera point's triangle: its fragments in a pool with hit payloads are the point's own
// surface, skipped by identity (blBundleSurfaceNearest).
uint gOwnTriangle = kBundleNil;

// The next surface from x along side * omega in bundle `slot`, across a closed room's creases too
// (blBundleSurfaceNearestAcrossCreases; bidir's pools carry hit payloads; `hitPixel`: the pixel
// whose centre ray holds it).
uint bidirSurfaceNearest(BundleNodes nodes, uint slot, BundleFrame frame, ivec2 bundlePixel, vec3 x, float depth,
                         vec3 n, float side, out float crossing, out ivec2 hitPixel) {
    return blBundleSurfaceNearestAcrossCreases(nodes, blBundlePoolHeads(push.pool, slot),
                                               BundleHitPayload(push.pool.payload), gOwnTriangle, frame, bundlePixel,
                                               x, depth, n, side, crossing, hitPixel);
}
#include "modes/bidir/EnvironmentDirect.glsl"
#include "modes/bidir/HitAlbedo.glsl"

// blBidirEvalBrdf with this pipeline's suppression; without glossy materials every BRDF is
// Lambert's (what blEvalBrdf returns for a material without a specular lobe).
vec3 bidirBrdf(GpuMaterial m, vec3 albedo, vec3 n, vec3 wi, vec3 wo, float density) {
    if (!kGlossy) {
        return blLambert(albedo);
    }
    return blBidirEvalBrdf(m, albedo, n, wi, wo, density, kSuppression, push.suppressionNeighbours);
}

// blEvalBrdf (no suppression), Lambert's without glossy materials.
vec3 bidirBrdfUnsuppressed(GpuMaterial m, vec3 albedo, vec3 n, vec3 wi, vec3 wo) {
    return kGlossy ? blEvalBrdf(m, albedo, n, wi, wo) : blLambert(albedo);
}

// The albedo at a bundle hit: its material's without textures in the scene.
vec3 bidirHitAlbedo(GpuMaterial m, vec2 uv) { return kTextured ? blPackedTextureAlbedo(m, uv) : m.albedo; }

// Directional sample densities (samples per steradian, [TO12] Eq. 15-17) of the one-bounce path
// x0 -> y -> x whose middle vertex y has area densities pA1 (VPL strategy) and pA2 (bundle
// strategy), pLight = P(l) p_e of the light ray: with p the density of the strategy in use (the
// sum for MIS) and N = gDensityPairs, d_{y,0} = N p |y - x0|^2 / cos_{y,0} = N p pLight / pA1 and
// d_{y,3} = N p |y - x|^2 / cos_{y,3} = N p p_r / pA2; dY = 1 / (1 / d_{y,0} + 1 / d_{y,3})
// (Eq. 13) at y, dX = d_{y,3} at x (the camera side is a delta). Zero densities give +inf.
float gDensityPairs; // N of Eq. 14-17: the pairs in this pixel's estimate (Interleave.h blInterleaveDensityPairs)
void oneBounceDensities(float pA1, float pA2, float pLight, out float dY, out float dX) {
    float p = kStrategy == kBidirStrategyVpl ? pA1 : (kStrategy == kBidirStrategyBundle ? pA2 : pA1 + pA2);
    float np = gDensityPairs * p;
    float inv0 = np > 0.0 && pLight > 0.0 ? pA1 / (np * pLight) : 0.0;
    float inv3 = np > 0.0 ? pA2 / (np * push.hemispherePdf) : 0.0;
    dY = inv0 + inv3 > 0.0 ? 1.0 / (inv0 + inv3) : 1e30;
    dX = inv3 > 0.0 ? 1.0 / inv3 : 1e30;
}

// The VPL sources: the point/spot lights, and the area emitters as one more where kAreaVpls
// (modes/bidir/VplSampler.h: a pair's source is uniform among them; the area source's VPLs carry
// light = lightCount).
float vplSources() { return float(push.lightCount + (kAreaVpls ? 1u : 0u)); }
bool fromAreaEmitters(BidirVpl v) { return kAreaVpls && v.light == push.lightCount; }

// The bundle strategy's count of samples of the light vertex per bundle hit, against a VPL's one:
// every point/spot light's shadow cube once, or the M emitter points for the area emitters.
float bundleLightSamples(BidirVpl v) { return fromAreaEmitters(v) ? float(blEmitterPointHeader.count) : 1.0; }

// Light l's direct light reflected at point p (normal n turned toward wo) toward wo, by its shadow
// cube; with the light ray's area density P(l) p_e cos / r^2 of p (MIS). pOther >= 0: p is the
// middle vertex of a one-bounce path whose bundle strategy has area density pOther: the BRDF at p
// is suppressed by its sample density (Suppression.h) and dX returns the density at the path's
// camera end; pOther < 0: direct light, no suppression.
vec3 lightAt(uint l, vec3 p, vec3 n, GpuMaterial m, vec3 albedo, vec3 wo, float pOther, out float areaPdf,
             out float dX) {
    areaPdf = 0.0;
    dX = 1e30;
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
    // Traced VPLs: the RSM block is empty and blBidirLightPdf would return this same density.
    float pLight = (kRsm ? blBidirLightPdf(l, light, fromLight) : blBidirEmissionPdf(light, fromLight)) / vplSources();
    areaPdf = pLight * cosine / r2;
    float visibility = blShadowVisibility(kShadowCubeFaces * l, push.shadowResolution, d, n);
    if (visibility <= 0.0) {
        return vec3(0.0);
    }
    float dY = 0.0; // no suppression
    if (pOther >= 0.0) {
        oneBounceDensities(areaPdf, pOther, pLight, dY, dX);
    }
    vec3 f = bidirBrdf(m, albedo, n, wi, wo, dY);
    return f * light.intensity * (profile * visibility * cosine / r2);
}

// The edge from point p (normal n turned toward the side it reflects on) to VPL k, shared by the
// one-bounce (p = x) and two-bounce (p = the bundle hit) terms: false when the VPL is invalid, p
// lies behind it or it behind p (reflection, not transmission), or its shadow cube hides p.
// Else wi (p toward the VPL), r2 = |VPL - p|^2, the cosines at p and at the VPL, visibility.
// v = vpls[k], loaded once per pair by the caller for both terms.
bool vplEdge(uint k, BidirVpl v, vec3 p, vec3 n, out vec3 wi, out float r2, out float cosP, out float cosV,
             out float visibility) {
    wi = vec3(0.0);
    cosP = cosV = visibility = 0.0;
    vec3 toVpl = v.position - p;
    r2 = dot(toVpl, toVpl);
    if (v.valid == 0u || !(r2 > 0.0)) {
        return false;
    }
    wi = toVpl * inversesqrt(r2);
    cosP = dot(n, wi);
    cosV = -dot(v.normal, wi);
    if (cosP <= 0.0 || cosV <= 0.0) {
        return false;
    }
    visibility = blShadowVisibilityTaps(kBidirMapVpl, kShadowCubeFaces * k, push.vplResolution, p - v.cubeCentre, n,
                                        kVplTaps);
    return visibility > 0.0;
}

// Strategy j = 1 of pair k (VPL v, its material mv) at x.
vec3 vplTerm(uint k, BidirVpl v, GpuMaterial mv, vec3 x, vec3 n, GpuMaterial m, vec3 albedo, vec3 wo) {
    vec3 wi;
    float r2, cosX, cosY, visibility;
    if (!vplEdge(k, v, x, n, wi, r2, cosX, cosY, visibility)) {
        return vec3(0.0);
    }
    float p2 = push.hemispherePdf * cosY / r2; // the bundle strategy's area density of y
    float dY, dX;
    oneBounceDensities(v.areaPdf, p2, v.pdfLight, dY, dX);
    vec3 fy = bidirBrdf(mv, v.albedo, v.normal, v.toLight, -wi, dY);
    vec3 fx = bidirBrdf(m, albedo, n, wi, wo, dX);
    // I f_y f_x G(y, x) / (P(l) p_e): the light ray's own cos/r^2 cancels against its area pdf.
    vec3 estimate = v.intensity * fy * fx * (visibility * cosX * cosY / (r2 * v.pdfLight));
    if (kStrategy == kBidirStrategyVpl) {
        return estimate;
    }
    // Balance heuristic with counts: the bundle strategy samples the light vertex bundleLightSamples
    // times per hit (x0 has the same density in both, p_A or the light's).
    return estimate * (v.areaPdf / (v.areaPdf + bundleLightSamples(v) * p2));
}

// Two-bounce path x0 -> x1 = VPL k -> x2 = y -> x ([TO12] Eq. 7-8), y the bundle hit of pair k
// (normal ny turned toward x, BRDF my, albedo ay) reached from x along d: everything but x's own factor
// f_{2,3,4} (n3.w_{3,2}) / p_r, which the caller shares with the one-bounce bundle term:
//   I f_{0,1,2} f_{1,2,3} G(x1, x2) V(x1, x2) / (P(l) p_e(w_{0,1})),
// the path's density p_{1,2} of Eq. 8 being P(l) p_e p_r |x1 - x2|^2 / (cos1 cos2). Visibility
// x1 - x2 from the VPL's shadow cube, shared with its one-bounce term. Clamping (this term
// only): |x1 - x2|^2 >= push.twoBounceMinDistance2, a bias stated in BidirMode.h.
vec3 twoBounceTerm(uint k, BidirVpl v, GpuMaterial mv, vec3 y, vec3 ny, GpuMaterial my, vec3 ay, vec3 wy) {
    vec3 wi;
    float r2, cos2, cos1, visibility; // cos2 at x2 = y, cos1 at x1 = the VPL
    if (!vplEdge(k, v, y, ny, wi, r2, cos2, cos1, visibility)) {
        return vec3(0.0);
    }
    vec3 f1 = bidirBrdfUnsuppressed(mv, v.albedo, v.normal, v.toLight, -wi);
    vec3 f2 = bidirBrdfUnsuppressed(my, ay, ny, wi, wy);
    float g = visibility * cos1 * cos2 / max(r2, push.twoBounceMinDistance2);
    return v.intensity * f1 * f2 * (g / v.pdfLight);
}

// Pair k's bundle from x: strategy j = 2 of the one-bounce term (returned; zero for strategy =
// vpl) and, with bounces = 2, the two-bounce term through the same hit y (added to `twoBounce`).
vec3 bundleTerm(uint k, BidirVpl v, GpuMaterial mv, vec3 x, vec3 n, GpuMaterial m, vec3 albedo, vec3 wo,
                inout vec3 twoBounce) {
    BundleFrame frame = blBundlePoolFrame(push.pool, k);
    float cosine = dot(n, frame.direction);
    float side = cosine >= 0.0 ? 1.0 : -1.0;
    vec3 d = side * frame.direction;
    ivec2 bundlePixel;
    float depth;
    if (!blBundlePixel(frame, x, bundlePixel, depth)) {
        gOutsideBundle = true; // the frame covers the scene's sphere or this frame's visible points
        return vec3(0.0);
    }
    BundleNodes nodes = BundleNodes(push.pool.nodes);
    float unusedCrossing; // y stays on the centre ray (below)
    ivec2 hitPixel = bundlePixel;
    uint hit = bidirSurfaceNearest(nodes, k, frame, bundlePixel, x, depth, n, side, unusedCrossing, hitPixel);
    if (hit == kBundleNil) {
        return vec3(0.0); // escapes: environment light is not bidir's one-bounce term
    }
    BundleHit payload = BundleHitPayload(push.pool.payload).hits[hit];
    // y on the bundle pixel's centre ray, up to half a pixel beside x's exact ray (the bundle
    // resolution's bias, shrinking with the pixel size): the surface point the fragment sampled.
    // Not moved onto x's ray (where multibounce puts its next vertex): y is where VPLs connect, and
    // a point on the fragment's plane beyond its polygon made the unclamped two-bounce term spiky
    // (Bidir.TwoBounceUnclampedConvergesToReferenceIndirect2: region 7 +10.4% +- 7%, noise gate).
    vec3 y = blBundlePixelRay(frame, vec2(hitPixel) + 0.5) + nodes.nodes[hit].depth * frame.direction;
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
    vec3 ay = bidirHitAlbedo(my, payload.uv); // textured
    float weightX = abs(cosine) / push.hemispherePdf;
    if (kBounces >= 2u) {
        // Eq. 14 at x for the two-bounce path: d = N p_r (d on the light side is a delta).
        vec3 fx2 = bidirBrdf(m, albedo, n, d, wo, gDensityPairs * push.hemispherePdf);
        twoBounce += twoBounceTerm(k, v, mv, y, ny, my, ay, wy) * fx2 * weightX;
    }
    if (kStrategy == kBidirStrategyVpl) {
        return vec3(0.0);
    }
    float p2 = push.hemispherePdf * max(cosY, 0.0) / r2;
    vec3 sum = vec3(0.0);
    for (uint l = 0u; l < push.lightCount; ++l) {
        float p1, dX;
        vec3 reflected = lightAt(l, y, ny, my, ay, wy, p2, p1, dX);
        float weight = kStrategy == kBidirStrategyBundle ? 1.0 : (p2 > 0.0 ? p2 / (p1 + p2) : 0.0);
        vec3 fx = bidirBrdf(m, albedo, n, d, wo, dX);
        sum += reflected * fx * (weight * weightX);
    }
    // Area emitters (emitter points, next-event estimation at y), against the area VPLs where they
    // exist (balance heuristic, blEmitterPointsSum's vplDensity: share 1 / vplSources()). Unlike the
    // lights' term above, no BRDF here is suppressed: the points' sum carries no sample density of
    // the path (the area VPLs' side is; a stated gap of the glossy suppression).
    if (blEmitterPointHeader.count > 0u) {
        float vplDensity = kAreaVpls && kStrategy == kBidirStrategyMis && p2 > 0.0 ? 1.0 / (vplSources() * kPi * p2) : 0.0;
        vec3 reflected = blEmitterPointsSum(y, ny, my, ay, wy, 0.0, vplDensity, true);
        sum += reflected * bidirBrdfUnsuppressed(m, albedo, n, d, wo) * weightX;
    }
    return sum;
}

void main() {
    // Interleaving: threads run in the split layout, each shading the pixel it gathers to.
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uint firstPair = 0u, pairStride = 1u;
    if (interleave.n > 1u) {
        pixel = blInterleaveGather(pixel, blInterleaveBlock(push.width, push.height, interleave.n), interleave.n);
        firstPair = blInterleaveSubImage(pixel, interleave.n);
        pairStride = interleave.n * interleave.n;
    }
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) {
        return;
    }
    // The pool contract: a build that ran out of nodes left lists incomplete; the mode grows the
    // pool and redoes the frame, so nothing of this one may be added.
    // pairs = 0 (no point/spot light): no pool is bound, its address is 0 and must not be read.
    if (push.pairs > 0u && (kStrategy != kBidirStrategyVpl || kBounces >= 2u) && blBundlePoolOverflowed(BundleCounterBlock(push.pool.counters))) {
        return;
    }
    if (!blCameraHitSurface(pixel)) {
        vec3 background[kPathLayerCount];
        for (uint l = 0u; l < kPathLayerCount; ++l) {
            background[l] = vec3(0.0);
        }
        background[kPathEmitted] = blCameraBackground(pixel, push.samplePosition, push.environmentPresent != 0u,
                                                      push.environmentRotation);
        emitSample(pixel, background);
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
    vec2 unusedBarycentrics;
    gOwnTriangle = blGBufferSurface(pixel, unusedBarycentrics);
    layers[kPathEmitted] = imageLoad(gbuffer[kGBufferEmission], pixel).rgb;
    for (uint l = 0u; l < push.lightCount; ++l) {
        float unusedPdf, unusedDensity;
        layers[kPathDirect] += lightAt(l, x, n, m, albedo, wo, -1.0, unusedPdf, unusedDensity);
    }
    if (kEnvironment) {
        layers[kPathDirect] += bidirEnvironmentDirect(x, n, m, albedo, wo);
    }
    layers[kPathDirect] += blEmitterPointsLight(x, n, m, albedo, wo, 0.0); // none where count = 0
    vec3 indirect = vec3(0.0);
    vec3 twoBounce = vec3(0.0);
    const bool bundles = kStrategy != kBidirStrategyVpl || kBounces >= 2u;
    const bool vplUsed = kStrategy != kBidirStrategyBundle || kBounces >= 2u;
    uint used = 0u; // pairs of this pixel's sub-image
    gDensityPairs = blInterleaveDensityPairs(
        push.pairs, firstPair < push.pairs ? (push.pairs - firstPair + pairStride - 1u) / pairStride : 0u,
        interleave.blurred);
    for (uint k = firstPair; k < push.pairs; k += pairStride, ++used) {
        BidirVpl v;
        GpuMaterial mv;
        if (vplUsed) {
            v = vpls[k]; // once for the pair's one- and two-bounce terms
            mv = materials[v.material];
        }
        if (kStrategy != kBidirStrategyBundle) {
            indirect += vplTerm(k, v, mv, x, n, m, albedo, wo);
        }
        if (bundles) {
            indirect += bundleTerm(k, v, mv, x, n, m, albedo, wo, twoBounce);
        }
    }
    if (gOutsideBundle) {
        return;
    }
    layers[kPathIndirect1] = indirect / float(max(used, 1u));
    layers[kPathIndirect2] = twoBounce / float(max(used, 1u));
    emitSample(pixel, layers);
}
