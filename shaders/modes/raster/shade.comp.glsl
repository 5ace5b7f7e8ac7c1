#version 460
#extension GL_GOOGLE_include_directive : require
// Raster mode shading: emitted radiance of visible emitters, direct light from point and spot
// lights with cube shadow maps (4x4 PCF), and the environment seen by rays that escape. Adds one
// sample per pixel to the running sum (w counts samples).
#include "modes/raster/RasterShared.h"
#include "shared/Bindings.h"
#include "shared/Brdf.h"
#include "shared/Camera.h"
#include "shared/CubeFaces.h"
#include "shared/EnvMap.h"
#include "shared/Lights.h"

layout(local_size_x = kRasterGroupSize, local_size_y = kRasterGroupSize) in;

layout(set = 0, binding = kRasterBindingGBuffer, rgba32f) uniform readonly image2D gbuffer[kGBufferAttachmentCount];
layout(set = 0, binding = kRasterBindingCamera) uniform CameraBlock { GpuCamera camera; };
layout(set = 0, binding = kRasterBindingMaterials) readonly buffer MaterialBlock { GpuMaterial materials[]; };
layout(set = 0, binding = kRasterBindingLights) readonly buffer LightBlock { GpuLight lights[]; };
layout(set = 0, binding = kRasterBindingShadowMaps, r32f) uniform readonly image2DArray shadowMaps;
layout(set = 0, binding = kRasterBindingEnvironment) uniform sampler2D environment;
layout(set = 0, binding = kRasterBindingAccum, rgba32f) uniform image2D accum;
layout(push_constant) uniform PushBlock { RasterPush push; };

// Projects direction d (from the light) onto its cube face: continuous texel coordinates.
vec2 faceTexel(vec3 d, uint face) {
    vec3 r, u, f;
    blCubeFaceBasis(face, r, u, f);
    float z = dot(d, f);
    vec2 xy = vec2(dot(d, r), dot(d, u)) / z;
    return vec2(xy.x + 1.0, 1.0 - xy.y) * (0.5 * float(push.shadowResolution));
}

// Fraction of 16 PCF taps that see the light from receiver point p (relative to the light) with
// normal n. Each tap compares the stored distance along its texel's centre ray with the distance at
// which that same ray meets the receiver's tangent plane, so a planar receiver never shadows itself
// and no scale-dependent bias is needed.
float shadowVisibility(uint light, vec3 p, vec3 n) {
    const float res = float(push.shadowResolution);
    uint face = blCubeFaceOf(p);
    vec3 r, u, f;
    blCubeFaceBasis(face, r, u, f);
    vec2 st = faceTexel(p, face);
    float lit = 0.0;
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
            vec2 tap = st + vec2(float(i) - 1.5, float(j) - 1.5);
            // Taps beyond the face continue on the neighbouring face.
            vec2 xy = vec2(tap.x / res * 2.0 - 1.0, 1.0 - tap.y / res * 2.0);
            vec3 dir = f + xy.x * r + xy.y * u;
            uint tapFace = blCubeFaceOf(dir);
            vec2 tapSt = tapFace == face ? tap : faceTexel(dir, tapFace);
            ivec2 texel = clamp(ivec2(floor(tapSt)), ivec2(0), ivec2(int(push.shadowResolution) - 1));
            vec3 tr, tu, tf;
            blCubeFaceBasis(tapFace, tr, tu, tf);
            vec2 c = (vec2(texel) + 0.5) / res * 2.0 - 1.0;
            vec3 centreRay = normalize(tf + c.x * tr - c.y * tu);
            float denom = dot(centreRay, n);
            if (denom >= -1e-6) {
                lit += 1.0; // the tap's ray runs parallel to or behind the receiver plane
                continue;
            }
            float receiver = dot(p, n) / denom;
            float stored = imageLoad(shadowMaps, ivec3(texel, int(6u * light + tapFace))).r;
            lit += stored >= receiver * (1.0 - kShadowRelativeBias) ? 1.0 : 0.0;
        }
    }
    return lit * (1.0 / 16.0);
}

vec3 shadeSurface(ivec2 pixel) {
    vec3 position = imageLoad(gbuffer[kGBufferPosition], pixel).xyz;
    vec4 normalMaterial = imageLoad(gbuffer[kGBufferNormal], pixel);
    vec3 albedo = imageLoad(gbuffer[kGBufferAlbedo], pixel).rgb;
    vec3 radiance = imageLoad(gbuffer[kGBufferEmission], pixel).rgb;
    vec3 n = normalMaterial.xyz;
    GpuMaterial m = materials[uint(normalMaterial.w)];
    vec3 wo = normalize(camera.position - position);
    for (uint i = 0u; i < push.lightCount; ++i) {
        GpuLight light = lights[i];
        vec3 d = position - light.position;
        float r2 = dot(d, d);
        if (!(r2 > 0.0)) {
            continue;
        }
        vec3 fromLight = d * inversesqrt(r2);
        vec3 wi = -fromLight;
        float cosine = dot(n, wi);
        float profile = blLightProfile(light, fromLight);
        if (cosine <= 0.0 || profile <= 0.0) {
            continue; // lit from the side the camera does not see, or outside the spot cone
        }
        float visibility = shadowVisibility(i, d, n);
        if (visibility <= 0.0) {
            continue;
        }
        vec3 f = blEvalBrdf(m, albedo, n, wi, wo);
        radiance += f * light.intensity * (profile * visibility * cosine / r2);
    }
    return radiance;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) {
        return;
    }
    vec3 radiance;
    if (imageLoad(gbuffer[kGBufferPosition], pixel).w > 0.0) {
        radiance = shadeSurface(pixel);
    } else if (push.environmentPresent != 0u) {
        vec3 dir = blCameraRayDirection(camera, vec2(pixel) + push.samplePosition);
        radiance = textureLod(environment, blEnvDirectionToUv(dir, push.environmentRotation), 0.0).rgb;
    } else {
        radiance = vec3(0.0);
    }
    if (any(isnan(radiance)) || any(isinf(radiance))) {
        return; // never averaged in: the pixel's sample count (w) does not grow, which counts it
    }
    imageStore(accum, pixel, imageLoad(accum, pixel) + vec4(radiance, 1.0));
}
