// Mode `bidir`: real-time bidirectional path tracing by rasterization ([TO12 Eq. 3]-[TO12 Eq. 8],
// papers/EQUATIONS.md): camera sub-paths by global ray-bundles, light sub-paths by virtual point lights,
// combined by multiple importance sampling.
//
// One iterate() = one frame: G-buffer, the lights' shadow cubes, then K pairs (pairs_per_frame) of
// {one VPL y_k on the first surface a light ray meets (modes/bidir/ReflectiveShadowMap.h or
// VplSampler.h: pdfs stated there), its shadow cube, one bundle along a random omega_k, its frame
// fitted to the points the G-buffer sees}, evaluated at every visible point x
// by shaders/modes/bidir/evaluate.comp.glsl:
//   VPL strategy (j = 1)    I f_{0,y,x} f_{y,x,o} G(y, x) V(y, x) / (P(l) p_e(omega_{0,y}))
//   bundle strategy (j = 2) I V(x0, y) (n_y.w_{y,0}) / |y - x0|^2 f_{0,y,x} f_{y,x,o} (n.d) / p_r(d),
//                           y = the next surface from x along d = +-omega_k in bundle k
//   mis                     each weighted by the balance heuristic p_Aj / (p_A1 + p_A2) of the
//                           area densities of y ([TO12] Eq. 3-6); for area emitters with counts,
//                           one VPL against the M emitter points at the bundle's hit.
// The mean over the K pairs is one sample of the `indirect1` layer (3 segments); `direct` (the
// lights by their shadow cubes, 4x4 PCF, as `raster`) and `emitted` are written beside it.
//
// Parameters (`bundlelab modes`):
//   pairs_per_frame        21       K VPL/bundle pairs per frame ([TO12] used 21)
//   strategy               mis      vpl | bundle | mis
//   bundle_resolution      256      pixels per side of each bundle
//   shadow_resolution      1024     texels per face side of the lights' shadow cubes
//   vpl_shadow_resolution  256      texels per face side of each VPL's shadow cube
//   vpl_shadow_taps        4        PCF taps a side of the VPL cubes' lookups (4: 4x4 as the lights'
//                                   cubes; 2 or 1: 4x / 16x fewer taps, a different filter of the
//                                   VPL shadows, its bias measured in experiments/bidir-table1.md)
//   directions             random   bundle directions: random or halton
//   memory_cap_mib         2048     bundle node pool limit (a frame that needs more is refused)
//   bounces                2        1: one-bounce only; 2: also the two-bounce term (Eq. 7-8): the
//                                   path light -> VPL k -> bundle k's hit -> x, visibility VPL-hit
//                                   from VPL k's shadow cube, layer `indirect2`. It needs both a VPL
//                                   and a bundle per pair, whatever `strategy` says.
//   two_bounce_clamp       0        clamping of the two-bounce term only: |x1 - x2| is taken as at
//                                   least this fraction of the scene's bounding radius in G(x1, x2)
//                                   (0: off, unbiased). A bias: energy lost near corners, measured
//                                   in tests/modes/bidir/BidirTest.cpp and papers/tokuyoshi-ogaki-2012.md.
//   suppression            none     glossy artifact suppression ([TO12] section 5,
//                                   shaders/modes/bidir/Suppression.h): none | clamp | roughness, at
//                                   both vertices of one-bounce paths (densities of Eq. 13-17 from
//                                   N = the pairs in the pixel's estimate of one frame: K, or K / n^2
//                                   with interleave = n and the blur off; per frame, so the bias
//                                   stays as frames accumulate) and at x of two-bounce paths (Eq.
//                                   14); the lights' direct term is never suppressed.
//   suppression_neighbours 16       m' ([TO12]: 16)
//   vpl_source             rsm      rsm: VPLs sampled on the GPU from a reflective shadow cube per
//                                   light rendered every frame with a sub-texel jitter, p_e by the
//                                   light's flux per texel (a spot light's profile included) and
//                                   textured albedo (modes/bidir/ReflectiveShadowMap.h). Region by
//                                   region the same as traced VPLs (Cornell box, point and spot
//                                   light, MIS, 8 vs 6 seeds x 512 frames: every 8x8 region's
//                                   rsm / traced ratio within 2 sigma, image 0.995 +- 0.005 and
//                                   1.004 +- 0.004; papers/tokuyoshi-ogaki-2012.md);
//                                   traced: first hits of light rays on the CPU (Embree,
//                                   VplSampler.h), p_e uniform on the sphere or I(omega) / integral(I)
//                                   for a spot: exact, the sampler the RSM is checked against.
//                                   Area emitters are one more VPL source either way (P = 1 / (L +
//                                   1)): x0 by power as the emitter points, a cosine-weighted CPU
//                                   ray (VplSampler::areaVpl; with rsm the cubes' pass leaves those
//                                   pairs to the host), combined with the emitter points at the
//                                   bundles' hits by the balance heuristic with counts (1 VPL
//                                   against M points), and the only source of their two-bounce
//                                   light.
//   rsm_resolution         256      texels per face side of the reflective shadow cubes ([TO12]: 256)
//   environment_bundles    21       E bundles per frame for direct environment light, directions by
//                                   Eq. 2's importance (L_o = 0.1 of the mean luminance), in the
//                                   same pool and fit (modes/bidir/EnvironmentBundles.h); skipped
//                                   without an environment. Indirect environment light: not yet.
//   fit                    visible  bundle frames: around the points the G-buffer sees this frame
//                                   ([TO12s] B.1, core bundleFrameForPoints; smaller pixels for the
//                                   same bundle_resolution) or the scene's bounding sphere (scene).
//                                   The frame spans the visible points' rays across the whole
//                                   depth of the scene's sphere, so hits no camera point sees (the
//                                   bundle strategy's and the two-bounce term's y) are all there
//                                   (tested with a camera that sees only the floor). A camera
//                                   point outside a bundle drops the pixel's sample (counter
//                                   dropped_samples; 0 by construction, tested).
//
//   interleave             1        n: n x n sub-images, each with every n^2-th pair, gathered and
//                                   blurred over the n x n neighbourhood ([TO12s] A.1,
//                                   modes/bidir/Interleaving.h); 1: off. pairs_per_frame >= n^2.
//   interleave_filter      on       on | off: the geometry-aware blur after the gather (off: each
//                                   pixel keeps its sub-image's K / n^2 pairs, unbiased)
//   temporal               off      on | off: 2 x 2 sub-pixel caches, round-robin with periodic
//                                   sample sets, reverse reprojection ([TO12s] A.2). The image is
//                                   the pixel sampled at the 2 x 2 sub-pixel centres (not the box
//                                   filter; ~1% of the image mean apart where the Cornell box's
//                                   edges cut pixels at 32^2); no bias of the reconstruction against
//                                   the reference: experiments/bidir-interleaving.md. Adds the EXR
//                                   layer cache_hits (the last frame's share of accepted caches).
//   reprojection           auto     auto | always: auto warps into the caches' cameras only when the
//                                   camera is animated (a static camera's warp is the identity)
//   temporal_depth_variance 1e-4    2 sigma^2 of the caches' log-depth Gaussian ([TO12s]: 1e-4)
//
// Textured albedo: at bundle hits (the payload's UV in the packed texture buffer) and at RSM VPLs
// (the RSM's G-buffer), and at traced VPLs (the hit's UV, atlas/AlbedoLookup.h: the G-buffer's
// sampling on the host). Not yet: indirect environment light (not lit here).
#pragma once

#include "bundle/BundlePool.h"
#include "bundle/DirectionSampler.h"
#include "modes/Mode.h"
#include "modes/bidir/BidirOptions.h"
#include "modes/bidir/Interleaving.h"

#include <memory>
#include <optional>

namespace bl {

class BidirMode final : public Mode {
public:
    static constexpr const char* kPairs = "pairs_per_frame";
    static constexpr const char* kStrategy = "strategy";
    static constexpr const char* kBundleResolution = "bundle_resolution";
    static constexpr const char* kShadowResolution = "shadow_resolution";
    static constexpr const char* kVplShadowResolution = "vpl_shadow_resolution";
    static constexpr const char* kVplShadowTaps = "vpl_shadow_taps";
    static constexpr const char* kDirections = "directions";
    static constexpr const char* kMemoryCap = "memory_cap_mib";
    static constexpr const char* kBounces = "bounces";
    static constexpr const char* kTwoBounceClamp = "two_bounce_clamp";
    static constexpr const char* kSuppression = "suppression";
    static constexpr const char* kSuppressionNeighbours = "suppression_neighbours";
    static constexpr const char* kVplSource = "vpl_source";
    static constexpr const char* kRsmResolution = "rsm_resolution";
    static constexpr const char* kEnvironmentBundles = "environment_bundles";
    static constexpr const char* kFit = "fit";
    static constexpr const char* kEmitterPoints = "emitter_points";
    static constexpr const char* kEmitterShadowResolution = "emitter_shadow_resolution";
    static constexpr const char* kInterleave = "interleave";
    static constexpr const char* kInterleaveFilter = "interleave_filter";
    static constexpr const char* kTemporal = "temporal";
    static constexpr const char* kReprojection = "reprojection";
    static constexpr const char* kTemporalDepthVariance = "temporal_depth_variance";

    // The ids of the plan's passes that setScene() and iterate() execute (BidirPlan.cpp).
    static constexpr const char* kBidirPassVpls = "vpls";
    static constexpr const char* kBidirPassAreaVpls = "area-vpls";
    static constexpr const char* kBidirPassBundles = "bundles";
    static constexpr const char* kBidirPassSuppression = "glossy-suppression";
    static constexpr const char* kBidirPassInterleave = "interleave";
    static constexpr const char* kBidirPassReprojection = "reprojection";
    static constexpr const char* kBidirPassEnvironment = "environment-bundles";
    static constexpr const char* kBidirPassEmitterPoints = "emitter-points";

    static std::vector<ParamSpec> parameters();
    static std::unique_ptr<Mode> create(const Settings& settings);

    explicit BidirMode(const Settings& settings);
    ~BidirMode() override;

    std::string_view name() const override { return "bidir"; }
    void setScene(const Scene& scene, vk::Context* gpu) override;
    void iterate(const IterationInfo& info) override;
    ImageSet resolve() override;
    const Settings& settings() const override { return mSettings; }
    PassTimes timings() const override;
    PassPlan plan(const Scene& scene) const override;
    TradeSettings trades() const override;

private:
    struct Gpu;
    void buildBundles(const IterationInfo& info);
    void setUpInterleaving(const Scene& scene, std::uint32_t width, std::uint32_t height);

    Settings mSettings;
    BidirOptions mOptions; // mSettings, typed, read once
    PassPlan mPlan;        // plan(scene) of the scene given to setScene: what iterate() runs
    const Scene* mScene = nullptr;
    vk::Context* mContext = nullptr;
    std::unique_ptr<Gpu> mGpu;
    std::uint32_t mIterations = 0;
    std::unique_ptr<Interleaving> mInterleave; // kept across setScene: the temporal caches
    const Scene* mInterleaveScene = nullptr;
};

} // namespace bl
