// Host/device definitions of bidir's spatio-temporal interleaved sampling ([TO12s Eq. 1],
// [TO12s Eq. 3] in papers/EQUATIONS.md; modes/bidir/Interleaving.h drives it, shaders/modes/bidir/
// interleave.comp.glsl resolves it).
//
// Spatial: the image is split into n x n sub-images, sub-image s = (p.y mod n) n + (p.x mod n)
// holding every n-th pixel; its pixels evaluate only the pairs k = s, s + n^2, s + 2 n^2, ... of the
// frame's K. The evaluation is dispatched in the split layout (sub-image (sx, sy) is the block of
// ceil(W / n) x ceil(H / n) threads at (sx, sy) times the block size, so a workgroup shares one
// pair subset) and gathered back to the pixel it shades; the geometry-aware blur then mixes the n x n
// sub-images around each pixel.
// Temporal: 2 x 2 sub-pixel caches of filtered indirect light with their view depth, cache c
// rewritten at frames c, c + 4, ... with the c-th fixed sample set, read back through reverse
// reprojection weighted by the log-depth Gaussian (their Eq. 1 and 3).
#ifndef BL_BIDIR_INTERLEAVE_H
#define BL_BIDIR_INTERLEAVE_H
#include "../../shared/Accumulation.h"
#include "../../shared/GpuTypes.h"

BL_NAMESPACE_BEGIN

// Resolve pass, set 1 (set 0 is the camera set).
BL_CONST uint kInterleaveSet = 1u;
BL_CONST uint kInterleaveBindingFrame = 0u;   // rgba32f 2D array, kPathLayerCount layers: this frame's layers
BL_CONST uint kInterleaveBindingCaches = 1u;  // rgba32f 2D array, 2 layers per cache (indirect1 + z, indirect2),
                                              // then kTemporalHitsLayer
BL_CONST uint kInterleaveBindingCameras = 2u; // storage InterleaveCache[kTemporalCaches]
BL_CONST uint kInterleaveGroupSize = 8u;

// The 2 x 2 sub-pixels of [TO12s] A.2: one indirect-light cache each.
BL_CONST uint kTemporalCaches = 4u;
// Layer of the cache image after the caches: the last frame's cache-hit ratio per pixel, x = the
// sum of the other caches' weights h_i over their number, kTemporalCaches - 1 (the denominator
// of their Eq. 1 less the current cache's h = 1, scaled to [0, 1]: their Fig. 1 b / 4 c); 0 where
// the pixel saw no surface or no other cache was written yet.
BL_CONST uint kTemporalHitsLayer = 2u * kTemporalCaches;
BL_CONST uint kTemporalCacheLayers = kTemporalHitsLayer + 1u;
// Their Eq. 3: h = exp(-log^2(z / z_c) / (2 sigma^2)) with 2 sigma^2 = 1e-4 "for all scenes" (the
// default of the mode's temporal_depth_variance).
BL_CONST float kTemporalTwoSigma2 = 1e-4f;
// Geometry-aware blur (the paper gives no weights): normal weight max(0, n.n_q)^8, and a Gaussian
// in the neighbour's distance from the pixel's tangent plane with scale 1% of the view depth.
BL_CONST float kFilterNormalPower = 8.0f;
BL_CONST float kFilterPlaneScale = 0.01f;
// Frame image, layer 0's w: written by the evaluation (1) or not (the clear value: dropped sample).
BL_CONST float kFrameWritten = 1.0f;
BL_CONST float kFrameDropped = -1.0f;

// What the resolve pass knows of cache i: the camera it was rendered with (reprojection target).
struct InterleaveCache {
    GpuCamera camera;
    uint valid; // 0 until the cache's first update
    uint pad0;
    uint pad1;
    uint pad2;
};
BL_STATIC_ASSERT(sizeof(InterleaveCache) == 144, "InterleaveCache layout");

// What the evaluation pass needs to know (BidirShared.h's kBidirBindingInterleave).
struct InterleaveEvaluate {
    uint n;      // sub-images per side (1: off)
    uint deferred; // 1: write the layers to the frame image for the resolve pass
    uint blurred;  // 1: the resolve pass blurs over the n x n sub-images (the pixel's estimate then
                   // holds all K pairs: blInterleaveDensityPairs)
    uint pad1;
};
BL_STATIC_ASSERT(sizeof(InterleaveEvaluate) == 16, "InterleaveEvaluate layout");

struct InterleavePush {
    uint width;
    uint height;
    uint interleave;   // n (1: off)
    uint blur;         // 1: geometry-aware blur over the n x n neighbourhood
    uint temporal;     // 1: caches + reconstruction
    uint cache;        // the cache this frame rewrites
    uint reproject;    // 1: warp into each cache's camera; 0: the camera is static (identity warp)
    float twoSigma2;   // 2 sigma^2 of the log-depth Gaussian
};
BL_STATIC_ASSERT(sizeof(InterleavePush) == 32, "InterleavePush layout");

// Sub-image of pixel p.
BL_INLINE uint blInterleaveSubImage(ivec2 p, uint n) {
    return uint(p.y % int(n)) * n + uint(p.x % int(n));
}

// Side of one sub-image's block in the split layout: ceil(size / n).
BL_INLINE ivec2 blInterleaveBlock(uint width, uint height, uint n) {
    return ivec2(int((width + n - 1u) / n), int((height + n - 1u) / n));
}

// Split layout position of pixel p, and back (gather). Positions past the image in the last
// block of a row or column gather to pixels outside the image (the caller skips them).
BL_INLINE ivec2 blInterleaveSplit(ivec2 p, ivec2 block, uint n) {
    return ivec2((p.x % int(n)) * block.x + p.x / int(n), (p.y % int(n)) * block.y + p.y / int(n));
}
BL_INLINE ivec2 blInterleaveGather(ivec2 t, ivec2 block, uint n) {
    return ivec2((t.x % block.x) * int(n) + t.x / block.x, (t.y % block.y) * int(n) + t.y / block.y);
}

// N of glossy suppression's sample densities ([TO12] Eq. 14-17: N p) at a pixel that evaluates
// `used` of the frame's `pairs`: [TO12] N is the number of samples in the pixel's estimate. With
// the blur (the paper's pipeline) that estimate mixes the n x n sub-images and holds all K pairs;
// without it, only the sub-image's K / n^2. (Temporal caches would add the caches that hit; N
// stays the frame's, as for progressive accumulation: the bias does not depend on the frames.)
BL_INLINE float blInterleaveDensityPairs(uint pairs, uint used, uint blurred) {
    return float(blurred != 0u ? pairs : used);
}

// 1D tap weight of the n x n blur at offset d in [-n/2, n/2]: for even n the two end taps share a
// sub-image and weigh 1/2 each, so every sub-image has the same total weight and the kernel stays
// centred (odd n: n unit taps).
BL_INLINE float blInterleaveTap(int d, uint n) {
    return ((n % 2u) == 0u && (d == int(n / 2u) || d == -int(n / 2u))) ? 0.5f : 1.0f;
}

// Centre of sub-pixel i of the 2 x 2 grid, in [0, 1)^2.
BL_INLINE vec2 blTemporalSubPixel(uint i) {
    return vec2(0.25f + 0.5f * float(i & 1u), 0.25f + 0.5f * float(i >> 1u));
}

// View depth of world point x in camera c (along its forward axis).
BL_INLINE float blTemporalViewDepth(GpuCamera c, vec3 x) { return dot(x - c.position, c.forward); }

// [TO12s] Eq. 3: weight of a cached sample at depth zc for a point at depth z in the cache's view.
BL_INLINE float blTemporalDepthWeight(float z, float zc, float twoSigma2) {
    float l = log(z / zc);
    return exp(-l * l / twoSigma2);
}

BL_NAMESPACE_END
#endif
