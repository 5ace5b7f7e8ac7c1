#version 460
#extension GL_GOOGLE_include_directive : require
// Mode multibounce, one camera path per pixel through K resident omnidirectional bundles ([TO12 §7],
// papers/EQUATIONS.md). From the G-buffer's visible point, each bounce picks a stored
// bundle k uniformly (random directions: among those the path has not just used), takes d = omega_k or -omega_k (the
// one on the shading normal's side: density p_r(d) = 1 / (2 pi) on that hemisphere for uniform
// directions), finds the point's place in its bundle pixel and the next fragment along d in the
// depth-sorted list: that fragment's hit payload is the next vertex. No ray is traced. Fragments are ordered by where x's own ray crosses their
// planes, x's own triangle skipped (bundle/Traversal.glsl: blBundleSurfaceNearest), so the
// winding of the faces does not matter and thin walls do not leak; where x's pixel has nothing
// ahead, its footprint's contact taps find a closed room's crease (blBundleSurfaceNearestAcrossCreases)
// so paths do not escape through it. With random directions (and
// any sequence when K <= 8) the bundles are drawn without replacement along a path (blMultibouncePickBundle): d is never the
// direction the path arrived along, and a path that has used all K <= 8 bundles ends. At every vertex: emission when the path meets an emitter's front face, point/spot light
// by cube shadow maps, the area emitters by this iteration's emitter points (gpu/EmitterPointLight.glsl),
// the environment by this iteration's environment directions (gpu/EnvironmentShadowLight.glsl) and
// when the path escapes. Emitters are reached two ways after a bounce, by a bundle and by an
// emitter point: the balance heuristic weighs the two (the bundle's density p_r(d) on the
// hemisphere against M p_A(y)), and gives the points the whole path where no bundle is left; the
// environment likewise by an escape and by its directions (p_r(d) against K q~(d)).
// Weights are f cos / p_r; Russian roulette after push.rrSegments segments. Textured albedo at every
// vertex from the packed texture buffer (gpu/PackedTextureLookup.glsl: no descriptor indexing),
// at the payload's UV (perfect bundles) or the splat's UV at the hit (imperfect bundles).
#include "modes/multibounce/MultibounceShared.h"
#define BL_MATERIAL_SPEC_FIRST kMultibounceSpecCount
#include "gpu/MaterialSpecialization.glsl"
#include "modes/multibounce/DrawSearch.glsl"
#include "bundle/Traversal.glsl"
#include "shared/Brdf.h"
#include "shared/Lights.h"
#include "shared/Octahedral.h"
#include "shared/Random.h"
#define BL_ACCUM_LAYERS kMultibounceAccumLayers
#include "gpu/CameraSet.glsl"
#define BL_SHADOW_SET kMultibounceSet
#define BL_SHADOW_BINDING kMultibounceBindingShadowMaps
#define BL_SHADOW_BINDING_2 kMultibounceBindingEmitterShadowMaps
#include "gpu/ShadowCubeLookup.glsl"
#include "gpu/ShadowedLight.glsl"
#define BL_EMITTER_POINTS_SET kMultibounceSet
#define BL_EMITTER_POINTS_BINDING kMultibounceBindingEmitterPoints
#include "gpu/EmitterPointLight.glsl"
#define BL_ENVIRONMENT_SHADOWS_SET kMultibounceSet
#define BL_ENVIRONMENT_SHADOWS_BINDING kMultibounceBindingEnvironmentShadows
#define BL_ENVIRONMENT_SHADOW_MAPS_BINDING kMultibounceBindingEnvironmentShadowMaps
#define BL_ENVIRONMENT_SHADOW_RADIANCE(d) environmentRadiance(d)
vec3 environmentRadiance(vec3 d);
#include "gpu/EnvironmentShadowLight.glsl"
#define BL_PACKED_TEXTURES_SET kMultibounceSet
#define BL_PACKED_TEXTURES_BINDING kMultibounceBindingTextures
#include "gpu/PackedTextureLookup.glsl"

layout(local_size_x = kMultibounceGroupSize, local_size_y = kMultibounceGroupSize) in;

layout(set = kMultibounceSet, binding = kMultibounceBindingLights) readonly buffer LightBlock { GpuLight lights[]; };
layout(set = kMultibounceSet, binding = kMultibounceBindingEmitters) readonly buffer EmitterBlock {
    MultibounceEmitter emitters[];
};
layout(set = kMultibounceSet, binding = kMultibounceBindingPoints) readonly buffer PointBlock {
    MultibouncePoint points[];
};
layout(set = kMultibounceSet, binding = kMultibounceBindingSplats) readonly buffer SplatBlock { BundleSplat splats[]; };
layout(push_constant) uniform PushBlock { MultibouncePush push; };
layout(constant_id = kMultibounceSpecPointLights) const bool kPointLights = true;
layout(constant_id = kMultibounceSpecEmitterPoints) const bool kEmitterPoints = true;
layout(constant_id = kMultibounceSpecEnvironment) const bool kEnvironmentShots = true;

// The environment's radiance toward d, as escaping paths and the MIS weights of its directions read it.
vec3 environmentRadiance(vec3 d) {
    return textureLod(environment, blEnvDirectionToUv(d, push.environmentRotation), 0.0).rgb;
}

// Layer of a contribution whose path has `segments` segments (1 = emitted, 2 = direct, ...).
uint layerOf(uint segments) { return min(segments, kPathLayerCount) - 1u; }

BL_DEFINE_DRAW_SEARCH(emitterOf, emitters)

// Emitted radiance of triangle `id`'s front face: that of the draw that holds it.
vec3 emissionOf(uint id) { return emitters[emitterOf(id, push.emitterCount)].emission; }

// Point and spot lights at x (normal n turned toward wo), visibility from the cube shadow maps.
vec3 directLight(vec3 x, vec3 n, GpuMaterial m, vec3 albedo, vec3 wo) {
    vec3 radiance = vec3(0.0);
    for (uint i = 0u; i < push.lightCount; ++i) {
        GpuLight light = lights[i];
        vec3 wi;
        float weight;
        if (blShadowedLightWeight(light, i, push.shadowResolution, x, n, wi, weight)) {
            radiance += blEvalBrdf(m, albedo, n, wi, wo) * light.intensity * weight;
        }
    }
    return radiance;
}

// One camera path from the G-buffer's vertex (x0 on triangle own0, n0 facing the camera, material
// m0), its contributions split by path length into `layers`.
void tracePath(vec3 x0, uint own0, vec3 n0, GpuMaterial m0, vec3 albedo0, vec3 emitted, uint pixelIndex,
               uint sampleIndex, out vec3 layers[kPathLayerCount]) {
    for (uint l = 0u; l < kPathLayerCount; ++l) {
        layers[l] = vec3(0.0);
    }
    vec3 x = x0;
    vec3 n = n0;
    GpuMaterial m = m0;
    vec3 albedo = albedo0;
    vec3 wo = normalize(camera.position - x);
    layers[kPathEmitted] = emitted;

    BundleNodes nodes = BundleNodes(push.pool.nodes);
    BundleHitPayload hits = BundleHitPayload(push.pool.payload);
    RandomStream rng = blRandomStream(push.seed, pixelIndex, sampleIndex);
    vec3 throughput = vec3(1.0);
    uint own = own0; // x's triangle: its fragments are x's own surface (perfect bundles)
    // Random directions, or K <= 8: bundles drawn without replacement along the path (MultibounceShared.h).
    MultibounceBundleWindow window =
        blMultibounceBundleWindow(push.pool.slots, (push.flags & kMultibounceDistinctBundles) != 0u);
    // x was reached by `segments` segments; its emission is counted.
    // The density the bundle strategy reaches an emitter with, for the MIS weights (0: the emitter
    // points alone, emitter_sampling = points).
    float bundlePdf = (push.flags & kMultibounceEmitterPointsOnly) != 0u ? 0.0 : push.hemispherePdf;
    for (uint segments = 1u; segments < push.maxSegments; ++segments) {
        bool bundleLeft = blMultibounceBundleLeft(window, push.pool.slots);
        vec3 lit = vec3(0.0);
        if (kPointLights) {
            lit += directLight(x, n, m, albedo, wo);
        }
        if (kEmitterPoints) {
            lit += blEmitterPointsLight(x, n, m, albedo, wo, bundleLeft ? bundlePdf : 0.0);
        }
        if (kEnvironmentShots) {
            lit += blEnvironmentShadowLight(x, n, m, albedo, wo, bundleLeft ? bundlePdf : 0.0);
        }
        layers[layerOf(segments + 1u)] += throughput * lit;

        if (!bundleLeft) {
            break; // every one of K <= 8 bundles drawn: no direction independent of the path's is left
        }
        vec2 u = blRandom2(rng);
        uint k = blMultibouncePickBundle(window, u.x, push.pool.slots);
        blMultibounceRemember(window, k);
        BundleFrame frame = blBundlePoolFrame(push.pool, k);
        float cosine = dot(n, frame.direction);
        float side = cosine >= 0.0 ? 1.0 : -1.0;
        vec3 d = side * frame.direction;
        vec3 weight = blEvalBrdf(m, albedo, n, d, wo) * (abs(cosine) / push.hemispherePdf);
        if (segments >= push.rrSegments) {
            vec3 next = throughput * weight;
            float survival = min(max(next.x, max(next.y, next.z)), kMultibounceMaxSurvival);
            if (!(u.y < survival)) {
                break;
            }
            weight /= survival;
        }
        throughput *= weight;

        ivec2 bundlePixel;
        float depth;
        if (!blBundlePixel(frame, x, bundlePixel, depth)) {
            break; // outside the frame around the scene's bounding sphere: cannot happen for scene points
        }
        // Splat payload ids are point indices: no identity to skip by (their normals are the planes).
        uint ownId = push.pointsPerDirection == 0u ? own : kBundleNil;
        float crossing;
        ivec2 unusedHitPixel; // the next vertex goes on x's own ray
        uint hit = blBundleSurfaceNearestAcrossCreases(nodes, blBundlePoolHeads(push.pool, k), hits, ownId, frame,
                                                       bundlePixel, x, depth, n, side, crossing, unusedHitPixel);
        if (hit == kBundleNil) {
            if ((push.flags & kMultibounceEnvironment) != 0u) {
                vec3 radiance = environmentRadiance(d);
                layers[layerOf(segments + 1u)] += throughput * radiance * blEnvironmentEscapeWeight(radiance, bundlePdf);
            }
            break;
        }
        BundleNode node = nodes.nodes[hit];
        BundleHit payload = hits.hits[hit];
        // The next vertex lies on x's own ray, on the plane of the fragment found on the centre ray
        // of x's bundle pixel or of one of its footprint's taps (up to 1.4 px beside it): where
        // that plane is not the surface x's ray meets (edges, curvature within the pixel), the
        // bundle-resolution bias, which shrinks with the pixel size. The payload (normal, UV) is
        // that centre ray's.
        float distance = abs(crossing - depth);
        x += (crossing - depth) * frame.direction;
        wo = -d;
        m = materials[payload.material & kBundleHitMaterialMask];
        uint triangle = payload.id;
        uint packedNormal = payload.normal;
        vec2 uv = payload.uv; // perfect bundles: at the pixel's ray
        if ((payload.material & kBundleHitSplat) != 0u) {
            // Imperfect bundles: a splat of bundle k's point set; its point holds the shading
            // normal, the triangle it was sampled on (the splat's face bit is that triangle's) and
            // the UV as a linear function over the splat's plane: evaluated at the hit x, as if
            // interpolated from texture coordinates at the splat's corners.
            uint index = k * push.pointsPerDirection + payload.id;
            MultibouncePoint point = points[index];
            triangle = point.triangle;
            packedNormal = point.normal;
            uv = point.uv;
            if ((push.flags & (kMultibounceTextured | kMultibounceSplatCentreUv)) == kMultibounceTextured) {
                vec3 offset = x - splats[index].position;
                vec2 a = unpackHalf2x16(point.gradientA), b = unpackHalf2x16(point.gradientB),
                     c = unpackHalf2x16(point.gradientC);
                uv += vec2(dot(vec3(a, b.x), offset), dot(vec3(b.y, c), offset));
            }
        }
        own = triangle;
        albedo = blPackedTextureAlbedo(m, uv);
        vec3 shading = blUnpackOctahedral(packedNormal);
        n = dot(shading, wo) >= 0.0 ? shading : -shading; // two-sided reflection
        if (blBundleFacesBack(node.next, side)) {
            // Front faces emit; weighed against the emitter points that reach the same point. The
            // cosine at the emitter is its shading normal's (its geometric one for flat emitters, as
            // the points use).
            vec3 emission = emissionOf(triangle);
            float weight = blEmitterHitWeight(emission, bundlePdf, abs(dot(shading, wo)), distance * distance);
            layers[layerOf(segments + 1u)] += throughput * emission * weight;
        }
    }
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) {
        return;
    }
    // The pool contract: a build that ran out of nodes left lists incomplete; the mode grows the
    // pool and redoes the iteration, so nothing of this one may be added.
    if (blBundlePoolOverflowed(BundleCounterBlock(push.pool.counters))) {
        return;
    }
    if (!blCameraHitSurface(pixel)) {
        vec3 background = blCameraBackground(pixel, push.samplePosition, (push.flags & kMultibounceEnvironment) != 0u,
                                             push.environmentRotation);
        for (uint s = 0u; s < push.pathsPerPixel; ++s) {
            blAccumulateLayer(pixel, kPathEmitted, background); // every pixel gets pathsPerPixel samples
        }
        return;
    }
    vec3 x0 = imageLoad(gbuffer[kGBufferPosition], pixel).xyz;
    vec4 normalMaterial = imageLoad(gbuffer[kGBufferNormal], pixel);
    GpuMaterial m0 = materials[uint(normalMaterial.w)];
    vec3 albedo0 = imageLoad(gbuffer[kGBufferAlbedo], pixel).rgb;
    vec3 emitted = imageLoad(gbuffer[kGBufferEmission], pixel).rgb;
    vec2 unusedBarycentrics;
    uint own0 = blGBufferSurface(pixel, unusedBarycentrics);
    uint pixelIndex = uint(pixel.y) * push.width + uint(pixel.x);
    for (uint s = 0u; s < push.pathsPerPixel; ++s) {
        vec3 layers[kPathLayerCount];
        tracePath(x0, own0, normalMaterial.xyz, m0, albedo0, emitted, pixelIndex, push.iteration * push.pathsPerPixel + s, layers);
        blAccumulate(pixel, layers);
    }
}
