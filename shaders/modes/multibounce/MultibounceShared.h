// Host/device definitions of mode multibounce (modes/multibounce/MultibounceMode.h): the path
// pass's set 1, push constants and emitter table. Set 0 is the camera set (core/gpu/CameraPass.h).
#ifndef BL_MULTIBOUNCE_SHARED_H
#define BL_MULTIBOUNCE_SHARED_H
#include "../../shared/Accumulation.h"
#include "../../shared/BundleTypes.h"

BL_NAMESPACE_BEGIN

// Path pass, set 1.
BL_CONST uint kMultibounceSet = 1u;
BL_CONST uint kMultibounceBindingLights = 0u;     // storage GpuLight[]
BL_CONST uint kMultibounceBindingShadowMaps = 1u; // storage image 2D array (rgba16ui, gpu/ShadowTexel.glsl), 6 layers per light
BL_CONST uint kMultibounceBindingEmitters = 2u;   // storage MultibounceEmitter[] (one per draw)
BL_CONST uint kMultibounceBindingPoints = 3u;     // storage MultibouncePoint[] (imperfect bundles)
BL_CONST uint kMultibounceBindingSplats = 4u;     // storage BundleSplat[] (imperfect bundles: the centres)
BL_CONST uint kMultibounceBindingTextures = 5u;   // storage uint[]: packed albedo textures (shared/PackedTextures.h)
BL_CONST uint kMultibounceBindingEmitterPoints = 6u;     // storage GpuEmitterPointHeader + GpuEmitterPoint[]
BL_CONST uint kMultibounceBindingEmitterShadowMaps = 7u; // storage image 2D array (rgba16ui, gpu/ShadowTexel.glsl), 6 layers per emitter point
BL_CONST uint kMultibounceBindingEnvironmentShadows = 8u;    // storage GpuEnvironmentShadowHeader + GpuEnvironmentShadow[]
BL_CONST uint kMultibounceBindingEnvironmentShadowMaps = 9u; // storage image 2D array (rgba32f: depth, normal), a depth map per direction

// MultibouncePush::flags.
BL_CONST uint kMultibounceEnvironment = 1u; // the scene has an environment: escaping paths gather it
BL_CONST uint kMultibounceTextured = 2u;    // some material has an albedo texture: UVs over splats evaluated at the hit
BL_CONST uint kMultibounceSplatCentreUv = 4u; // imperfect bundles: the UV of the splat's centre for the whole
                                              // splat (splat_uv = centre, for comparison), not the UV at the hit
BL_CONST uint kMultibounceDistinctBundles = 8u; // a path's bundles are drawn without replacement
                                                // (independent random directions: MultibounceBundleWindow)
// emitter_sampling = points: the emitter points (and the environment's directions) alone light each
// vertex (an emitter a bundle meets after a bounce, and the sky a path escapes to, weigh 0); without
// this flag and with points, both strategies by MIS.
BL_CONST uint kMultibounceEmitterPointsOnly = 16u;

// Emission of the triangles of one draw: triangle id t belongs to the last entry with
// firstTriangle <= t (entries in GpuScene draw order, so firstTriangle ascends). Radiance of the
// front face.
struct MultibounceEmitter {
    vec3 emission;
    uint firstTriangle;
};
BL_STATIC_ASSERT(sizeof(MultibounceEmitter) == 16, "MultibounceEmitter layout");

struct MultibouncePush {
    BundlePoolView pool;       // the K resident, sorted bundles of this iteration
    uint width;                // camera image
    uint height;
    uint seed;                 // run seed
    uint iteration;            // iteration index: decorrelates iterations
    uint lightCount;
    uint shadowResolution;     // texels per cube-face side
    uint emitterCount;
    uint flags;                // kMultibounce* flags above
    float environmentRotation; // radians about +y
    uint maxSegments;          // at most this many segments per path (1 = emitters only)
    uint rrSegments;           // segments before Russian roulette starts
    float hemispherePdf;       // p_r(d) of a bundle direction on a point's hemisphere: 1 / (2 pi)
    vec2 samplePosition;       // sub-pixel position of this iteration's camera sample, in [0, 1)^2
    uint pathsPerPixel;        // camera paths per pixel through this iteration's bundles
    uint pointsPerDirection;   // imperfect bundles: splats of each bundle (bundle k's are points
                               // k * pointsPerDirection ...); 0: perfect bundles of triangles
};
BL_STATIC_ASSERT(sizeof(MultibouncePush) == 128, "MultibouncePush layout");

BL_CONST uint kMultibounceGroupSize = 8u;

// Imperfect bundles ([TO12p]): what a path vertex found on a point splat needs beyond the bundle's
// hit payload, per point (the payload's id is the point's index within its direction's set). The
// poster gives each splat corner its texture coordinates; the same linear function of position in
// the splat's plane is stored as the UV at the centre and its world-space gradient, so
// uv(x) = uv + (dot(grad u, x - c), dot(grad v, x - c)) at the hit x of a splat centred at c.
struct MultibouncePoint {
    uint normal;        // octahedral shading normal (interpolated vertex normals), world space
    uint triangle;      // the triangle the point was sampled on (GpuScene order): its emission
    vec2 uv;            // material texture coordinates at the point (0 when no material is textured)
    uint gradientA;     // world-space UV gradient in half floats: packHalf2x16(du/dx, du/dy),
    uint gradientB;     // packHalf2x16(du/dz, dv/dx),
    uint gradientC;     // packHalf2x16(dv/dy, dv/dz)
    uint pad0;
};
BL_STATIC_ASSERT(sizeof(MultibouncePoint) == 32, "MultibouncePoint layout");

// Point pass: the scene's draws at the iteration's time, for the triangle -> draw search.
struct MultibounceDraw {
    mat4 model;         // rigid transform at the bundles' time
    uint firstTriangle; // global index of the draw's first triangle (ascending over the table)
    uint material;
    uint vertexOffset;
    uint pad0;
};
BL_STATIC_ASSERT(sizeof(MultibounceDraw) == 80, "MultibounceDraw layout");

BL_CONST uint kMultibouncePointsBindingCdf = 0u;      // storage float[]: area CDF over triangles
BL_CONST uint kMultibouncePointsBindingDraws = 1u;    // storage MultibounceDraw[]
BL_CONST uint kMultibouncePointsBindingVertices = 2u; // storage GpuVertex[]
BL_CONST uint kMultibouncePointsBindingIndices = 3u;  // storage uint[]
BL_CONST uint kMultibouncePointsBindingPlanes = 4u;   // storage vec4[] (GpuScene planes)
BL_CONST uint kMultibouncePointsBindingSplats = 5u;   // storage BundleSplat[] (written)
BL_CONST uint kMultibouncePointsBindingPoints = 6u;   // storage MultibouncePoint[] (written)

struct MultibouncePointsPush {
    uint seed;
    uint iteration;
    uint count;         // points in all: directions * pointsPerDirection
    uint pointsPerDirection;
    uint triangleCount;
    uint drawCount;
    float radius;       // splat radius, world units
    uint textured;      // 0: no material has a texture, UVs and their gradients are not computed (left 0)
};
BL_STATIC_ASSERT(sizeof(MultibouncePointsPush) == 32, "MultibouncePointsPush layout");
BL_CONST uint kMultibouncePointsGroupSize = 64u;

// Russian roulette never keeps a path with probability above this: a path whose throughput stays
// near 1 (white furnace) still ends, at the cost of 5% more variance per surviving segment.
BL_CONST float kMultibounceMaxSurvival = 0.95f;

// Bundles a path excludes when it draws the next one: those of its last 8 segments, all of them
// when K <= 8. A path that has drawn every one of K <= 8 bundles ends there: drawing again would
// repeat a cycle of the same K lines (K = 1: back and forth along one line; K = 2..9 with a window
// of K - 1, the one bundle left, a fixed cycle), whose weights f cos / p_r multiply without the
// independence they assume; measured on the point-lit Cornell box (32^2, 2048 directions, seeds
// 1-3) such paths made random-direction images 2x to 300x too bright at K = 2 and 3. Ending them
// keeps the paths of up to K bundle segments exact and drops the longer ones (their energy is the
// bias, stated by SettingTrades before rendering). For K > 8 a bundle can come back 9 or more
// segments later, when Russian roulette has ended nearly every path.
BL_CONST uint kMultibounceRecentBundles = 8u;

// The bundles of a path's last segments, oldest first: `count` of at most `size` =
// min(kMultibounceRecentBundles, K).
//
// For independent random directions, and for any sequence when K <= 8 (kMultibounceDistinctBundles,
// MultibounceMode::distinctBundles; size 0 otherwise: every draw uniform over all K). Halton
// directions are stratified within an iteration: each bundle stands for
// its stratum, and excluding the one a path arrived by leaves the stratum around -d unsampled.
// Measured on the point-lit Cornell box (32^2, 32 iterations, K = 64, seeds 1..4, against a
// 2048-spp reference): indirect2 0.99..1.04 with replacement, 0.94..0.98 without; the retro point
// mass of the draw with replacement (issue 19, B2) then stays: small at the default K = 64, large
// at small K (SettingTrades warns).
struct MultibounceBundleWindow {
    uint bundles[kMultibounceRecentBundles];
    uint count;
    uint size;
};

BL_INLINE MultibounceBundleWindow blMultibounceBundleWindow(uint slots, bool distinct) {
    MultibounceBundleWindow w;
    for (uint i = 0u; i < kMultibounceRecentBundles; ++i) {
        w.bundles[i] = 0u;
    }
    w.count = 0u;
    w.size = distinct ? min(kMultibounceRecentBundles, slots) : 0u;
    return w;
}

// False when a path without replacement has drawn all K bundles (K <= 8): it ends.
BL_INLINE bool blMultibounceBundleLeft(MultibounceBundleWindow w, uint slots) {
    return w.size == 0u || w.count < slots;
}

// The bundle of the next segment from u in [0, 1): uniform over the `slots` bundles not in the
// window. With replacement a path went back along the bundle it arrived by with probability
// 1 / K: its previous vertex again, a point mass the weight 1 / p_r treats as a continuous density
// (issue 19, B2). Without replacement the bundles of a path are distinct, so for independent
// uniform directions each d is uniform and independent of the path so far: p_r(d) = 1 / (2 pi)
// on x's hemisphere holds as before.
BL_INLINE uint blMultibouncePickBundle(MultibounceBundleWindow w, float u, uint slots) {
    uint excluded[kMultibounceRecentBundles];
    for (uint i = 0u; i < w.count; ++i) { // ascending, by insertion (count <= 8)
        uint v = w.bundles[i];
        uint j = i;
        for (; j > 0u && excluded[j - 1u] > v; --j) {
            excluded[j] = excluded[j - 1u];
        }
        excluded[j] = v;
    }
    uint available = slots - w.count;
    uint k = min(uint(u * float(available)), available - 1u);
    for (uint i = 0u; i < w.count; ++i) { // the k-th unused index: step over the used ones below it
        if (k >= excluded[i]) {
            ++k;
        }
    }
    return k;
}

// Bundle k was drawn: it joins the window, the oldest leaving a full one.
BL_INLINE void blMultibounceRemember(BL_INOUT(MultibounceBundleWindow) w, uint k) {
    if (w.size == 0u) {
        return;
    }
    if (w.count == w.size) {
        for (uint i = 1u; i < w.size; ++i) {
            w.bundles[i - 1u] = w.bundles[i];
        }
        --w.count;
    }
    w.bundles[w.count] = k;
    ++w.count;
}

// Every layer of the reference: emitted, direct, indirect1, indirect2, rest.
BL_CONST uint kMultibounceAccumLayers = kAllPathLayers;

// Specialization constants of the paths pass: which kinds of light the scene's plan runs (1) or
// leaves out (0), compiled out where left out (a SIMD CPU driver runs a loop's body at least once
// under a lane mask even with no light to loop over; RasterShared.h has the same three).
BL_CONST uint kMultibounceSpecPointLights = 0u;   // point and spot lights (their shadow cubes)
BL_CONST uint kMultibounceSpecEmitterPoints = 1u; // emitter points (area emitters)
BL_CONST uint kMultibounceSpecEnvironment = 2u;   // environment directions
BL_CONST uint kMultibounceSpecCount = 3u; // then the material constants (gpu/MaterialSpecialization.glsl)

BL_NAMESPACE_END
#endif
