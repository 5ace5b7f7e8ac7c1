// Host/device definitions of mode atlas (modes/atlas/AtlasMode.h): the texel and triangle tables,
// the per-direction parameters and the push constants of its compute passes and view raster.
// Every buffer is reached by device address, so the atlas can be any size without bindings.
#ifndef BL_ATLAS_SHARED_H
#define BL_ATLAS_SHARED_H
#include "../../shared/Accumulation.h"
#include "../../shared/BundleTypes.h"

BL_NAMESPACE_BEGIN

// Radiance is stored per texel and per side of the surface: reflection is two-sided, so the two
// sides of a thin wall see different light, and one value per texel would leak it through.
// Side 0 is the front (the side its counter-clockwise corners face; the only side that emits).
BL_CONST uint kAtlasSides = 2u;
BL_CONST uint kAtlasFront = 0u;
BL_CONST uint kAtlasBack = 1u;

// What the exchange needs of texel t (index (page * height + y) * width + x).
struct AtlasTexel {
    vec3 emission;     // radiance emitted from the front side
    float inverseArea; // 1 / world area of the surface whose atlas uv falls in the texel; 0: none
    vec3 albedo;       // Lambertian reflectance
    uint material;     // scene material index (its glossy lobe: the direct pass's glossy transfer)
};
BL_STATIC_ASSERT(sizeof(AtlasTexel) == 32, "AtlasTexel layout");

// Atlas uv (in [0, 1] of its page) of the corners of one GpuScene triangle, in drawing order:
// a bundle hit's barycentrics (b1, b2) give uv = (1 - b1 - b2) uv0 + b1 uv1 + b2 uv2.
struct AtlasTriangle {
    vec2 uv0;
    vec2 uv1;
    vec2 uv2;
    uint page;
    uint pad0;
};
BL_STATIC_ASSERT(sizeof(AtlasTriangle) == 32, "AtlasTriangle layout");

// A sample point inside a texel's preimage (modes/atlas/TexelSamples.h), for direct light from
// point and spot lights gathered per texel by shadow maps.
struct AtlasSample {
    vec3 position; // world space
    float weight;  // world area per uv area of its triangle
    vec3 normal;   // geometric, front side
    uint texel;
};
BL_STATIC_ASSERT(sizeof(AtlasSample) == 32, "AtlasSample layout");

// Direct pass: one invocation per texel averages point/spot light over its samples, both sides.
// Glossy passes (glossy transfer with point/spot lights): one invocation per glossy texel of a
// list; kAtlasDirectGlossyCache (once, at set-up) keeps each sample's light per light (direction,
// irradiance, the side it lights), kAtlasDirectGlossy (per direction) evaluates the lobes toward
// the next direction from it: the shadow lookups run once, not per direction.
struct AtlasDirectPush {
    uvec2 samples;    // AtlasSample[] grouped by texel
    uvec2 first;      // uint per texel + 1: its first sample
    uvec2 texels;     // AtlasTexel[]
    uvec2 direct;     // vec4 per texel side: reflected radiance of point/spot light (written)
    uvec2 sender;     // vec4 per texel side: set to emission + direct (the first direction's sender)
    uint texelCount;
    uint lightCount;
    uint shadowResolution;
    uint directIntoSender; // 1: sender = emission + direct (interleaved); 0: emission only (bounce pass 1)
    uvec2 received;   // glossy pass: uint[kAtlasReceivedWords] per texel side, its glossy transfer words
    vec3 next;        // glossy pass: the next direction omega_{i+1}
    uint glossy;      // kAtlasDirectAtlas, kAtlasDirectGlossyCache or kAtlasDirectGlossy
    uvec2 materials;  // glossy passes: GpuMaterial[]
    uvec2 touched;    // glossy pass: AtlasTouched (the sides it writes join the update's list)
    uvec2 glossyTexels; // glossy passes: uvec2 (texel, first record of its samples) per glossy texel
    uvec2 lightCache; // glossy passes: AtlasLightRecord per sample of a glossy texel and light
    uint glossyCount; // entries of glossyTexels
    uint pad0;
    uvec2 pad1;       // a multiple of 16 bytes (the struct's std430 size in the shader's block)
};
BL_STATIC_ASSERT(sizeof(AtlasDirectPush) == 128, "AtlasDirectPush layout");
BL_CONST uint kAtlasDirectAtlas = 0u;
BL_CONST uint kAtlasDirectGlossy = 1u;
BL_CONST uint kAtlasDirectGlossyCache = 2u;

// One light at one sample point of a glossy texel: the direction toward the light and its shadowed
// irradiance on the side it lights (blShadowedLight), side kAtlasSides where it lights neither.
struct AtlasLightRecord {
    vec3 toLight;
    uint side;
    vec3 irradiance;
    uint pad0;
};
BL_STATIC_ASSERT(sizeof(AtlasLightRecord) == 32, "AtlasLightRecord layout");
// First shot (first_shot = auto | on): each direction, the light of that iteration's emitter points
// (gpu/EmitterPointPass.h) and environment directions at a texel's sample points (shot_samples =
// one: one of them, drawn by its area; all: every one) joins a running sum, and the direct atlas
// becomes the point/spot lights' part + the sum's mean; the sender records' constant part is that,
// without the emission, so the exchange carries reflected light only (first_shot.comp.glsl).
struct AtlasFirstShotPush {
    uvec2 samples;     // AtlasSample[] grouped by texel
    uvec2 first;       // uint per texel + 1
    uvec2 texels;      // AtlasTexel[]
    uvec2 direct;      // vec4 per texel side: written, point/spot part + the shots' mean
    uvec2 pointDirect; // vec4 per texel side: the point/spot lights' part (the direct pass's)
    uvec2 shotSum;     // vec4 per texel side: the sum of the shots so far (written)
    uvec2 senders;     // AtlasSenderRecord per texel side: `base` written
    uint texelCount;
    float inverseShots; // 1 / the shots summed after this one
    uint shot;          // the shots summed before this one (shot_samples = one: which sample point)
    uint seedHash;      // blHash of the run seed (shot_samples = one: each seed its own rotations)
};
BL_STATIC_ASSERT(sizeof(AtlasFirstShotPush) == 72, "AtlasFirstShotPush layout");
// Specialization constant of the first shot (constant_id = index): 1 (shot_samples = all) lights
// every sample point of a texel each shot; 0 (one) one of them, drawn by its area weight.
BL_CONST uint kAtlasShotSpecAllSamples = 0u;
BL_CONST uint kAtlasShotSpecCount = 1u;
BL_CONST uint kAtlasFirstShotSet = 0u;
BL_CONST uint kAtlasFirstShotBindingPoints = 0u; // GpuEmitterPointHeader + GpuEmitterPoint[]
BL_CONST uint kAtlasFirstShotBindingMaps = 1u;   // the points' cubes (map 0 of the lookup; unused)
BL_CONST uint kAtlasFirstShotBindingMaps2 = 2u;  // the same image as map 1, which EmitterPointLight reads
// The environment's part (environment_shots = K > 0): K directions drawn by its importance, a depth
// map each (bundle/EnvironmentShadowPass.h; off: no directions, placeholders bound).
BL_CONST uint kAtlasFirstShotBindingEnvironment = 3u;     // GpuEnvironmentShadowHeader + GpuEnvironmentShadow[]
BL_CONST uint kAtlasFirstShotBindingEnvironmentMaps = 4u; // their depth maps (rgba32f 2D array: depth, normal)


BL_CONST uint kAtlasDirectSet = 0u;
BL_CONST uint kAtlasDirectBindingLights = 0u;     // GpuLight[] storage buffer
BL_CONST uint kAtlasDirectBindingShadowMaps = 1u; // rgba16ui 2D-array storage image (ShadowCubePass, gpu/ShadowTexel.glsl)

// What a texel side sends under interleaved transfer, in parts that change only where the side
// received light: the sender radiance is base + sum / W + glossy (AtlasBuffers.glsl:
// blAtlasSender), W the total weight of the directions before, so the update rewrites only the
// sides a direction touched while every side's mean follows W. One record (48 bytes, read together).
struct AtlasSenderRecord {
    vec3 base;   // emission + direct (split: direct only), written once before the first direction
    uint tag;    // index of the direction that stored `glossy`: it is sent by the next direction only
    vec3 sum;    // the weighted sum over directions (sum + compensation; the one-bounce channel where split)
    uint pad0;
    vec3 glossy; // glossy transfer toward the next direction (the lobes' reflection)
    uint pad1;
};
BL_STATIC_ASSERT(sizeof(AtlasSenderRecord) == 48, "AtlasSenderRecord layout");

// Parameters of one direction, written by the host before its submission: the direction's own
// numbers, and how the sender radiance of a texel side is formed (AtlasBuffers.glsl:
// blAtlasSender, from AtlasSenderRecord). Split channels (delay_indirect, [HHGM10] section 6.4): the one-bounce
// estimate (light of emitters and environment reflected once) and the multi-bounce estimate are
// summed apart; emitters send into the first, reflected light into the second.
struct AtlasDirection {
    vec3 environmentForward;  // environment radiance arriving from +omega (escapes past a list's end)
    float weight;             // a_pix / (pi p_r): bundle pixel area over (pi x hemisphere density)
    vec3 environmentBackward; // arriving from -omega (escapes before a list's first hit)
    uint glossy;              // 1: glossy texels store what they reflect toward +-next (glossy transfer)
    vec3 next;                // the next direction omega_{i+1} (glossy transfer atlas, [HHGM10] 5.4)
    float inverseDensity;     // 1 / p_r(omega): the final glossy gather's direction weight
    uvec2 texels;             // AtlasTexel[] (emission, split only)
    uvec2 senders;            // interleaved: AtlasSenderRecord per side
    uvec2 sumsIndirect;       // split: vec4[2] per side, the multi-bounce weighted sum
    uvec2 pad0;
    uvec2 pad1;
    uvec2 fixedSender;        // bounce: vec4 per side, the pass's sender
    uvec2 touched;            // AtlasTouched list of the sides this direction changes
    uvec2 receivedIndirect;   // split: uint[4] per side, this direction's multi-bounce reflection
    float scale;              // 1 / sum of w over the directions before this one (0: none)
    float indirectScale;      // split: the same over the multi-bounce channel's directions
    uint previous;            // index of the previous direction: its glossy transfer is sent now
    uint transfer;            // kAtlasTransferInterleaved or kAtlasTransferBounce
    uint split;               // 1: one-bounce and multi-bounce channels apart (delay_indirect > 0)
    uint indirect;            // split: 1 once indirect light is enabled (reflected light is sent)
    float weightIndirect;     // split: w of this direction in the multi-bounce channel
    uint clearIndirect;       // split: 1 on the multi-bounce channel's first direction (gather sums)
};
BL_STATIC_ASSERT(sizeof(AtlasDirection) == 144, "AtlasDirection layout");

// The list of texel sides a direction changed (exchange and glossy lights append, the update
// visits only these): words [count, groups, 1, 1, slot...]; words 1..3 are the update's
// indirect dispatch (groups of kAtlasGroupSize), reset to count = groups = 0 per direction.
BL_CONST uint kAtlasTouchedHeader = 4u;
BL_CONST uint kAtlasTouchedDispatchOffset = 4u; // bytes: the dispatch's (groups, 1, 1)

// Words per texel side of the `received` atlas: this direction's diffuse reflection (float bits,
// rgb in 0..2; the one-bounce channel where split), word 3 set once the side is in the touched
// list, and the glossy transfer atlas (rgb in 4..6): the radiance the side's glossy lobe reflects
// toward the next direction, sent by the next direction's exchange.
BL_CONST uint kAtlasReceivedWords = 8u;
BL_CONST uint kAtlasReceivedTouched = 3u;
BL_CONST uint kAtlasReceivedGlossy = 4u;

// Exchange pass: one invocation per bundle pixel walks its sorted list.
struct AtlasExchangePush {
    BundlePoolView pool;
    uvec2 texels;     // AtlasTexel[]
    uvec2 triangles;  // AtlasTriangle[] per GpuScene triangle
    uvec2 pad1;
    uvec2 received;   // uint[kAtlasReceivedWords] per texel side: this direction's reflected radiance and
                      // the glossy transfer atlas (float bits, CAS adds)
    uvec2 direction;  // AtlasDirection (with how the sender is formed)
    uvec2 materials;  // GpuMaterial[] (the glossy lobes of the glossy transfer)
    uint width;       // atlas page
    uint height;
    uint pages;
    uint pad0;
};
BL_STATIC_ASSERT(sizeof(AtlasExchangePush) == 128, "AtlasExchangePush layout");

// Update pass: one invocation per texel side of the touched list (or, where a bounce pass
// settles, per texel side) folds the direction's received radiance into the compensated sums over
// directions, clears the receiver and keeps the glossy transfer for the next direction.
struct AtlasUpdatePush {
    uvec2 texels;
    uvec2 sender;     // bounce: vec4 per texel side, the pass's sender (rewritten where a pass settles)
    uvec2 received;
    uvec2 sums;       // vec4[2] per texel side: sum over directions and its Neumaier compensation
    uint texelCount;  // width * height * pages
    float weight;     // w_j of this direction in the weighted mean (AtlasMode.h: weighting)
    float inverseTotalWeight; // 1 / sum of w over the directions so far, this one included
    uint clearSums;   // 1: start the sums over (this direction is the first)
    uvec2 direct;     // vec4 per texel side: point/spot light reflected (direct pass), part of the sender
    uvec2 settled;    // vec4 per texel side: sum of the finished bounce passes' means (transfer = bounce)
    uint transfer;    // kAtlasTransferInterleaved or kAtlasTransferBounce
    uint settle;      // bounce: this direction ends its pass (its mean settles and becomes the sender)
    uint directIntoSender; // bounce: the settling pass's sender gets the direct atlas too (pass 1 ends)
    uint mode;        // kAtlasUpdateListed, kAtlasUpdateAll or kAtlasUpdateInit
    uvec2 touched;    // AtlasTouched
    uvec2 senders;    // interleaved: AtlasSenderRecord per side (sum, glossy transfer and its tag)
    uvec2 receivedIndirect; // split: uint[4] per side, multi-bounce reflection (0: not split)
    uvec2 sumsIndirect;     // split: vec4[2] per side
    float weightIndirect;   // split: w of this direction in the multi-bounce channel (0: not yet enabled)
    uint iteration;   // index of this direction (the tag of the glossy transfer it stores)
};
BL_STATIC_ASSERT(sizeof(AtlasUpdatePush) == 120, "AtlasUpdatePush layout");
BL_CONST uint kAtlasUpdateListed = 0u; // the sides on the touched list
BL_CONST uint kAtlasUpdateAll = 1u;    // every side (a bounce pass settles)
BL_CONST uint kAtlasUpdateInit = 2u;   // every side's sender record, once before the first direction

// Transfer schemes ([HHGM10] section 5.5). Interleaved: the sender is rewritten after every
// direction (emission + direct + the running mean). Bounce: the sender is fixed for a pass of
// directions (pass 1: emission; pass b: pass b - 1's mean, + direct after pass 1), the pass's mean
// settles into the `settled` atlas when it ends; paths of at most max_segments segments.
BL_CONST uint kAtlasTransferInterleaved = 0u;
BL_CONST uint kAtlasTransferBounce = 1u;

// View raster: the camera's visible surface with its atlas uv, page and side.
struct AtlasViewPush {
    mat4 viewProj; // the camera's, with the sample's sub-pixel jitter folded in
    mat4 model;    // the mesh's rigid transform at the scene time
};
BL_STATIC_ASSERT(sizeof(AtlasViewPush) == 128, "AtlasViewPush layout");

// Shade pass: per camera pixel, the emission seen plus the reflected radiance of its texel side.
struct AtlasShadePush {
    uvec2 sums;            // vec4[2] per texel side (update pass)
    uvec2 texels;          // AtlasTexel[]: texels without area never receive (bilinear skips them)
    uvec2 charts;          // int per texel: bilinear lookups stay inside the sample's chart
    uint width;            // camera image
    uint height;
    uint atlasWidth;
    uint atlasHeight;
    float reflectedScale;  // 1 / total weight of the directions summed (0: nothing reflected yet)
    uint bilinear;         // 1: bilinear between texel centres inside the chart, 0: the texel alone
    vec2 samplePosition;   // sub-pixel camera sample, for background rays
    uint environmentPresent;
    float environmentRotation;
    uvec2 direct;          // vec4 per texel side: point/spot light reflected, to layer `direct`
    uvec2 settled;         // vec4 per texel side: finished bounce passes (transfer = bounce), to `rest`
    float directScale;     // 1, or 0 where the path length limit leaves out reflected light
    uint pad0;
    uvec2 gathered;        // vec4 per pixel: weighted sum of the final glossy gather (0: none), to `rest`
    uvec2 highlight;       // vec4 per pixel: point/spot light's glossy lobe toward the eye (0: none), to `direct`
    uvec2 sumsIndirect;    // split (delay_indirect): the multi-bounce channel's sums, to `rest`; the
                           // one-bounce `sums` (and `gathered`) then go to `direct`
    uvec2 gatheredIndirect; // split: the multi-bounce channel's gather sums, to `rest`
    float indirectScale;   // split: 1 / total weight of the multi-bounce channel (0: not enabled yet)
    uint split;
};
BL_STATIC_ASSERT(sizeof(AtlasShadePush) == 128, "AtlasShadePush layout");

// Final glossy gather ([HHGM10] section 5.3), after each direction's exchange: per camera pixel
// whose visible point p is glossy, the neighbour fragment of p along the direction on p's side
// sends its radiance, weighted by p's glossy lobe toward the eye, cos, 1 / p_r and w_j.
struct AtlasGatherPush {
    BundlePoolView pool;
    uvec2 gatheredIndirect; // split: vec4 per pixel, the multi-bounce channel's weighted sum
    uvec2 triangles;  // AtlasTriangle[]
    uvec2 gathered;   // vec4 per pixel: the weighted sum over directions (the one-bounce channel where split)
    uvec2 direction;  // AtlasDirection (what the neighbour sends: blAtlasSender)
    uvec2 pad0;
    uint width;       // camera image
    uint height;
    uint atlasWidth;
    uint atlasHeight;
    float weight;     // w_j of this direction (the atlas's weighted mean)
    uint clear;       // 1: the first direction, the sums start over
};
BL_STATIC_ASSERT(sizeof(AtlasGatherPush) == 128, "AtlasGatherPush layout");

// Point/spot light reflected by the glossy lobe toward the eye (the view's direct highlight),
// one invocation per camera pixel per view sample, into a per-pixel buffer the shade pass adds.
struct AtlasHighlightPush {
    uvec2 highlight;  // vec4 per pixel (written)
    uint width;
    uint height;
    uint lightCount;
    uint shadowResolution;
    uint pad0;
    uint pad1;
};
BL_STATIC_ASSERT(sizeof(AtlasHighlightPush) == 32, "AtlasHighlightPush layout");
BL_CONST uint kAtlasHighlightLightSet = 1u; // the direct pass's light set (GpuLight[], shadow cubes)

// Specialization constants of the exchange pass (exchange.comp.glsl), constant_id = index: the
// transfer paths the mode's plan fixes for the pipeline's life (AtlasMode::setScene). The
// direction's words (AtlasDirection: split, glossy, transfer) say the same, and the exchange reads
// them narrowed by these; as constants the compiler drops the paths a run never takes, which
// lavapipe, running both sides of every branch under a lane mask, otherwise pays for on every
// bundle pixel (experiments/bench/results/specialization-lavapipe-2026-11-28.md).
BL_CONST uint kAtlasSpecSplit = 0u;  // 1: split channels (delay_indirect)
BL_CONST uint kAtlasSpecGlossy = 1u; // 1: the glossy transfer atlas
BL_CONST uint kAtlasSpecBounce = 2u; // 1: bounce-by-bounce transfer (a fixed sender), 0: interleaved
BL_CONST uint kAtlasSpecCount = 3u;

BL_CONST uint kAtlasGroupSize = 64u;     // 1D passes (bundle pixels, texel sides)
BL_CONST uint kAtlasViewGroupSize = 8u;  // 2D shade pass

// The view pass's attachment: (u, v, page, side + 1); w = 0 where the camera ray escaped.
BL_CONST uint kAtlasViewSet = 1u;
BL_CONST uint kAtlasViewBinding = 0u;    // storage image rgba32f, the view attachment

// Layers: emitters and the environment seen directly (1 segment) in `emitted`; point and spot
// light reflected once (shadow maps, 2 segments) in `direct`; everything the exchange brings (area
// emitters' and the environment's direct light included: the exchange does not separate path
// lengths) in `rest`.
BL_CONST uint kAtlasAccumLayers = (1u << kPathEmitted) | (1u << kPathDirect) | (1u << kPathRest);

BL_NAMESPACE_END
#endif
