#version 460
#extension GL_GOOGLE_include_directive : require
// Skylight ([TO12] section 3, Fig. 6): for every camera-visible point x with normal n, the bundle
// direction d in {omega, -omega} on n's side is tested for occlusion in the bundle, and
//   L_e(d) f(x, d, w_o) (n.d) / p_r(d)
// is added (direct layer), with the emitted radiance of visible emitters (emitted layer), as one
// sample of the pixel. Points of other tiles are left to their tile; the tile with addBase handles
// the pixels whose camera ray escapes (the environment behind the scene).
//
// Control variate (controlVariate != 0): the Lambert part of the unoccluded sample,
//   h(d) = L_e(d) (albedo / pi) (n.d),  whose integral (albedo / pi) E(n) is tabulated
// (modes/skylight/IrradianceTable.h), is subtracted from the sample and its integral added:
//   (albedo / pi) E(n) + [V L_e f (n.d) - L_e (albedo / pi) (n.d)] / p(d).
// Same mean (up to the table's error); a diffuse point no occluder hides adds exactly
// (albedo / pi) E(n) every iteration, so bundles only estimate what occluders remove.
//
// Glossy control variate (glossyControl != 0): the same for the glossy lobe, whose unoccluded
// integral G = int L_e(l) f_g(l, w_o) (n.l) dl has no table but an unbiased estimate of low variance
// from one direction l drawn from the lobe itself (density p_g), environment looked up, no visibility:
//   L_e(l) f_g (n.l) / p_g(l) + [V L_e f_g (n.d) - L_e f_g (n.d)] / p(d).
// A sharp lobe is met by the lobe sample every iteration, not once in e + 1 bundle directions; the
// bundles carry only the lobe light occluders remove (-(1 - V) L_e f_g (n.d) / p(d)). Both terms read
// the same environment (premultiplied map, bilinear, as EnvironmentLight::radiance on the host).
#include "bundle/Traversal.glsl"
#include "modes/skylight/SkylightShared.h"
#define BL_ACCUM_LAYERS kSkylightAccumLayers
#include "gpu/CameraSet.glsl"
#include "gpu/BundleEnvironmentLight.glsl"
#include "shared/BrdfSampling.h"
#include "shared/Random.h"

layout(local_size_x = kSkylightGroupSize, local_size_y = kSkylightGroupSize) in;

layout(set = kSkylightSet, binding = kSkylightBindingFrame) uniform FrameBlock { BundleFrame frame; };
layout(set = kSkylightSet, binding = kSkylightBindingDepthMap, rgba32f) uniform readonly image2D depthMap;
#define BL_DEPTH_MAP_TEXEL(pixel, layer) imageLoad(depthMap, pixel)
#include "bundle/DepthMapVisibility.glsl"
layout(push_constant) uniform PushBlock { SkylightPush push; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SkylightIrradiance { vec4 entries[]; };

// E(n), bilinear between the table's normals (as IrradianceTable::lookup).
vec3 blSkylightIrradiance(vec3 n) {
    SkylightIrradiance table = SkylightIrradiance(push.irradianceAddress);
    vec2 t;
    uvec4 i = blSkylightIrradianceTaps(n, t);
    return mix(mix(table.entries[i.x].rgb, table.entries[i.y].rgb, t.x),
               mix(table.entries[i.z].rgb, table.entries[i.w].rgb, t.x), t.y);
}

// Both visibilities count what lies past x's own surface by blBundleSurfaceEpsilon, whatever its
// winding (bundle/Traversal.glsl). The bundles' walk is multibounce's: every fragment placed by its
// facet's plane from the hit payload, x's own triangle skipped, a closed room's creases found by
// the footprint's taps behind their gate. (Without the payload every fragment was taken parallel
// to x's plane: on a finely tessellated mesh a small concave facet beside x rose in front of it,
// and the bunny under a constant sky read 0.73 of the reference's direct light at 512^2; 0.91 now.)
bool occluded(BlBundleLightSample s, ivec2 bundlePixel, vec3 x, float depth, vec3 n, uint ownTriangle) {
    if (push.visibility == kSkylightVisibilityBundle) {
        float unusedCrossing;
        ivec2 unusedHitPixel;
        return blBundleSurfaceNearestAcrossCreases(BundleNodes(push.nodeAddress), BundleHeads(push.headAddress),
                                                   BundleHitPayload(push.hitAddress), ownTriangle, frame, bundlePixel,
                                                   x, depth, n, s.side, unusedCrossing, unusedHitPixel) != kBundleNil;
    }
    // The map keeps the surface nearest the light (bundle/DepthMapVisibility.glsl): only the
    // direction toward omega can be tested.
    return blDepthMapOccluded(frame, 0, bundlePixel, x, depth, n, dot(n, frame.direction));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) {
        return;
    }
    // Recorded in the build's own submission (BundleBuilder): an overflowed build is built again
    // (grown or tiled) and this pass recorded again, so this one adds nothing.
    if (push.visibility == kSkylightVisibilityBundle &&
        blBundlePoolOverflowed(BundleCounterBlock(push.counterAddress))) {
        return;
    }
    if (!blCameraHitSurface(pixel)) {
        if (push.addBase != 0u) {
            blAccumulateLayer(pixel, kPathEmitted, blCameraBackground(pixel, push.samplePosition,
                                                                      push.environmentPresent != 0u,
                                                                      push.environmentRotation));
        }
        return;
    }
    vec3 position = imageLoad(gbuffer[kGBufferPosition], pixel).xyz;
    ivec2 bundlePixel;
    float depth;
    if (!blBundlePixel(frame, position, bundlePixel, depth)) {
        return; // another tile's point
    }
    vec4 normalMaterial = imageLoad(gbuffer[kGBufferNormal], pixel);
    vec3 n = normalMaterial.xyz;
    BlBundleLight light = BlBundleLight(push.radianceForward, push.pdfForward, push.radianceBackward,
                                        push.pdfBackward, push.visibility == kSkylightVisibilityDepthMap);
    BlBundleLightSample s = blBundleLightSample(frame, light, n);
    vec3 layers[kPathLayerCount];
    for (uint l = 0u; l < kPathLayerCount; ++l) {
        layers[l] = vec3(0.0);
    }
    vec3 albedo = imageLoad(gbuffer[kGBufferAlbedo], pixel).rgb;
    vec2 unusedBarycentrics;
    uint ownTriangle = blGBufferSurface(pixel, unusedBarycentrics);
    if (s.usable && !occluded(s, bundlePixel, position, depth, n, ownTriangle)) {
        vec3 wo = normalize(camera.position - position);
        layers[kPathDirect] = blBundleLightContribution(s, materials[uint(normalMaterial.w)], albedo, n, wo);
    }
    if (push.controlVariate != 0u) {
        vec3 lambert = blLambert(albedo);
        if (s.usable) {
            layers[kPathDirect] -= s.radiance * lambert * (s.cosine / s.pdf);
        }
        layers[kPathDirect] += lambert * blSkylightIrradiance(n);
    }
    GpuMaterial material = materials[uint(normalMaterial.w)];
    if (push.glossyControl != 0u && blHasGlossyLobe(material)) {
        vec3 wo = normalize(camera.position - position);
        if (s.usable) {
            layers[kPathDirect] -= s.radiance * blGlossyBrdf(material, n, s.direction, wo) * (s.cosine / s.pdf);
        }
        RandomStream random = blRandomStream(push.seed, uint(pixel.y) * push.width + uint(pixel.x), push.iteration);
        vec3 l = blSampleGlossyLobe(material, n, wo, blRandom2(random));
        float pdf = blGlossyLobePdf(material, n, wo, l);
        float cosL = dot(n, l);
        if (cosL > 0.0 && pdf > 0.0 && push.environmentPresent != 0u) {
            vec3 radiance = textureLod(environment, blEnvDirectionToUv(l, push.environmentRotation), 0.0).rgb;
            layers[kPathDirect] += radiance * blGlossyBrdf(material, n, l, wo) * (cosL / pdf);
        }
    }
    // Each point lies in exactly one tile: it adds its emission and its sample there.
    layers[kPathEmitted] = imageLoad(gbuffer[kGBufferEmission], pixel).rgb;
    blAccumulate(pixel, layers);
}
