#version 460
#extension GL_GOOGLE_include_directive : require
// Skylight ([TO12] section 3, Fig. 6): for every camera-visible point x with normal n, the bundle
// direction d in {omega, -omega} on n's side is tested for occlusion in the bundle, and
//   L_e(d) f(x, d, w_o) (n.d) / p_r(d)
// is added (direct layer), with the emitted radiance of visible emitters (emitted layer), as one
// sample of the pixel. Points of other tiles are left to their tile; the tile with addBase handles
// the pixels whose camera ray escapes (the environment behind the scene).
#include "bundle/Traversal.glsl"
#include "modes/skylight/SkylightShared.h"
#define BL_ACCUM_LAYERS kSkylightAccumLayers
#include "gpu/CameraSet.glsl"
#include "gpu/BundleEnvironmentLight.glsl"

layout(local_size_x = kSkylightGroupSize, local_size_y = kSkylightGroupSize) in;

layout(set = kSkylightSet, binding = kSkylightBindingFrame) uniform FrameBlock { BundleFrame frame; };
layout(set = kSkylightSet, binding = kSkylightBindingDepthMap, r32f) uniform readonly image2D depthMap;
layout(push_constant) uniform PushBlock { SkylightPush push; };

bool occluded(BlBundleLightSample s, ivec2 bundlePixel, float depth) {
    if (push.visibility == kSkylightVisibilityBundle) {
        uint head = blBundleHead(BundleHeads(push.headAddress), frame, bundlePixel);
        return blBundleNearest(BundleNodes(push.nodeAddress), head, depth, s.side, s.ownSurface, frame) != kBundleNil;
    }
    // The map keeps the surface nearest the light: anything beyond the point's own surface along
    // omega occludes it (no face test: a shadow map has no faces).
    return imageLoad(depthMap, bundlePixel).r > depth + s.ownSurface;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) {
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
    if (s.usable && !occluded(s, bundlePixel, depth)) {
        vec3 albedo = imageLoad(gbuffer[kGBufferAlbedo], pixel).rgb;
        vec3 wo = normalize(camera.position - position);
        layers[kPathDirect] = blBundleLightContribution(s, materials[uint(normalMaterial.w)], albedo, n, wo);
    }
    // Each point lies in exactly one tile: it adds its emission and its sample there.
    layers[kPathEmitted] = imageLoad(gbuffer[kGBufferEmission], pixel).rgb;
    blAccumulate(pixel, layers);
}
