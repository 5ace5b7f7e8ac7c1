#version 460
#extension GL_GOOGLE_include_directive : require
// Skylight ([TO12] section 3, Fig. 6): for every camera-visible point x with normal n, the bundle
// direction d in {omega, -omega} on n's side is tested for occlusion in the bundle, and
//   L_e(d) f(x, d, w_o) (n.d) / p_r(d)
// is added, with the emitted radiance of visible emitters and one sample to the pixel's count.
// Points of other tiles are left to their tile; the tile with addBase handles the pixels whose
// camera ray escapes (the environment behind the scene).
#include "bundle/Traversal.glsl"
#include "modes/skylight/SkylightShared.h"
#include "shared/Bindings.h"
#include "shared/Brdf.h"
#include "shared/Camera.h"
#include "shared/EnvMap.h"

layout(local_size_x = kSkylightGroupSize, local_size_y = kSkylightGroupSize) in;

layout(set = 0, binding = kSkylightBindingGBuffer, rgba32f) uniform readonly image2D gbuffer[kGBufferAttachmentCount];
layout(set = 0, binding = kSkylightBindingCamera) uniform CameraBlock { GpuCamera camera; };
layout(set = 0, binding = kSkylightBindingMaterials) readonly buffer MaterialBlock { GpuMaterial materials[]; };
layout(set = 0, binding = kSkylightBindingFrame) uniform FrameBlock { BundleFrame frame; };
layout(set = 0, binding = kSkylightBindingAccum, rgba32f) uniform image2D accum;
layout(set = 0, binding = kSkylightBindingEnvironment) uniform sampler2D environment;
layout(set = 0, binding = kSkylightBindingDepthMap, r32f) uniform readonly image2D depthMap;
layout(push_constant) uniform PushBlock { SkylightPush push; };

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) {
        return;
    }
    vec4 position = imageLoad(gbuffer[kGBufferPosition], pixel);
    vec3 added = vec3(0.0);
    float samples = 0.0;
    if (position.w == 0.0) {
        if (push.addBase == 0u) {
            return;
        }
        if (push.environmentPresent != 0u) {
            vec3 dir = blCameraRayDirection(camera, vec2(pixel) + push.samplePosition);
            added = textureLod(environment, blEnvDirectionToUv(dir, push.environmentRotation), 0.0).rgb;
        }
        samples = 1.0;
    } else {
        ivec2 bundlePixel;
        float depth;
        if (!blBundlePixel(frame, position.xyz, bundlePixel, depth)) {
            return; // another tile's point
        }
        vec4 normalMaterial = imageLoad(gbuffer[kGBufferNormal], pixel);
        vec3 n = normalMaterial.xyz;
        float c = dot(n, frame.direction);
        float side = c >= 0.0 ? 1.0 : -1.0; // use omega or -omega, whichever is on n's side
        bool usable = push.visibility == kSkylightVisibilityBundle || side > 0.0;
        float cosine = abs(c);
        vec3 d = side * frame.direction;
        vec3 le = side > 0.0 ? push.radianceForward : push.radianceBackward;
        float pdf = side > 0.0 ? push.pdfForward : push.pdfBackward;
        if (usable && cosine > 0.0 && pdf > 0.0 && dot(le, le) > 0.0) {
            float tangent = min(sqrt(max(0.0, 1.0 - cosine * cosine)) / cosine, kSkylightMaxTangent);
            float own = frame.depthEpsilon + kSkylightOwnSurfacePixels * frame.pixelSize * tangent;
            bool occluded;
            if (push.visibility == kSkylightVisibilityBundle) {
                uint head = blBundleHead(BundleHeads(push.headAddress), frame, bundlePixel);
                occluded = blBundleNearest(BundleNodes(push.nodeAddress), head, depth, side, own, frame) != kBundleNil;
            } else {
                // The map keeps the surface nearest the light: anything beyond the point's own
                // surface along omega occludes it (no face test: a shadow map has no faces).
                occluded = imageLoad(depthMap, bundlePixel).r > depth + own;
            }
            if (!occluded) {
                GpuMaterial m = materials[uint(normalMaterial.w)];
                vec3 albedo = imageLoad(gbuffer[kGBufferAlbedo], pixel).rgb;
                vec3 wo = normalize(camera.position - position.xyz);
                added = le * blEvalBrdf(m, albedo, n, d, wo) * (cosine / pdf);
            }
        }
        // Each point lies in exactly one tile: it adds its emission and its sample there.
        added += imageLoad(gbuffer[kGBufferEmission], pixel).rgb;
        samples = 1.0;
    }
    if (any(isnan(added)) || any(isinf(added))) {
        return; // never averaged in: the pixel's sample count does not grow
    }
    imageStore(accum, pixel, imageLoad(accum, pixel) + vec4(added, samples));
}
