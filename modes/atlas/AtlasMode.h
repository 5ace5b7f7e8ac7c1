// Mode `atlas`: diffuse global illumination by radiance exchange in a texture atlas along global
// ray-bundles ([HHGM10] Hermes, Henrich, Grosch, Mueller, VMV 2010; [HHGM10 Eq. 3], [HHGM10 §5.3] in papers/EQUATIONS.md;
// papers/hermes-2010.md).
//
// Discretization. Every surface is a set of atlas texels (core/atlas); each texel T stands for the
// surface whose atlas uv falls in it (area A_T, exact: modes/atlas/AtlasTables.h) and keeps one
// outgoing radiance per side (front, back: reflection is two-sided, emission front only), assumed
// constant over T and over directions (Lambertian).
//
// One iteration = one global direction omega (Halton by default). The bundle along omega is built
// with the hit payload and depth-sorted: consecutive hits y, x of a pixel's list are consecutive
// surface crossings of the pixel's ray, so they see each other, y along +omega and x along -omega.
// Each pair exchanges radiance both ways ([HHGM10] Eq. 3); the first hit's -omega side and the last
// hit's +omega side see the environment (when the scene has one and its light was not shot: the
// first shot, AtlasFirstShot.cpp, then lit every texel directly and the list ends receive nothing).
//
// Estimator. The reflected radiance of side s of T is the area average
//   L_r(T) = 1/A_T  int_T  int_{H_s} (rho/pi) L_in(x, w) cos(theta) dw dA(x).
// The direction w = +-omega on H_s has density p_r = 1/(2 pi) (uniform omega; either sign serves
// one hemisphere), so one direction gives int_{H_s} ... dw ~ (rho/pi) L_in cos / p_r. The bundle
// samples the surface with parallel rays a_pix = pixelSize^2 apart: the ray of a pixel stands for
// the surface area a_pix / |cos| around its hit, so int_T g dA ~ sum over the pixels hitting T of
// g a_pix / |cos|. The cosines cancel:
//   L_r(T) ~ sum_{pixels p hitting side s of T} rho_T L_sender(p) a_pix / (pi p_r A_T)
// = 2 rho_T a_pix / A_T per pixel for uniform directions, the quantity the exchange pass adds to
// T (its "received" atlas). Averaged over N directions (the grid's phase is random through the
// frame's random rotation about omega), the expected pixel count times a_pix is A_T |cos| averaged,
// and the mean is unbiased for the area average given L_sender. Every direction counts for every
// texel, hit or not: the estimate is sum / N.
//
// Interleaved transfer (Gauss-Seidel, their default): after every direction the sender atlas
// becomes emission + the current estimate, so direction i sends light of up to i bounces. The
// first directions therefore carry fewer bounces, and a plain mean over n directions keeps their
// deficit: it is a stochastic fixed-point iteration with step 1/n, whose deficit decays only as
// n^-(1 - rho) (rho: the scene's effective reflectance; the furnace, rho = 1/2, lacks 2.1% after
// 256 directions, measured). The estimate is therefore a weighted mean, direction j weighted
// w_j = j^k (`weighting` = k): the deficit decays as n^-((k + 1)(1 - rho)) (furnace, k = 2:
// n^-1.5), at the price of an effective sample count n (2k + 1) / (k + 1)^2 (k = 2: 0.56 n).
// k = 0 is the plain mean.
// The deficit is exact (tests/modes/atlas/AtlasBias.h) for directions drawn independently. The
// default Halton sequence in its own order is not: each point fills the gaps the points before
// it left, so direction j depends on the estimate it carries, and the mean falls short by a
// further ~1/n (furnace, of its 2: 0.76 / n at 32 directions, 1.1 / n at 128, 1.3 / n at 512;
// the mode matches the recursion run over each seed's own directions to 1e-4). It is kept for its lower variance (furnace RMSE at
// 128 directions 0.0085 against 0.0115 for `directions = random`, which has none of it).
//
// Cost per direction. The update visits only the texel sides the direction touched (the exchange
// and the glossy lights pass append them to a list, AtlasTouched; an indirect dispatch), not the
// whole atlas: interleaved transfer keeps no sender atlas that every side's new mean would have to
// rewrite, but per side a record (AtlasSenderRecord: emission + direct, the sum, the glossy
// transfer and the direction that stored it) from which the exchange forms the sender as
// base + sum / W + glossy, the same float steps as the rewritten atlas (images equal to the last
// bit but for the exchange's atomic float adds, whose order varies run to run). The price is in
// the exchange (a 48-byte record read per sender, a mark and a list entry per side touched): on
// lavapipe it grew ~1.5-2x while the update fell from ~0.2 us per texel side to ~0 (2048^2 atlas,
// 512^2 bundles: ~8x less per direction; 1024^2: about even).
//
// Delayed indirect light ([HHGM10] section 6.4, `delay_indirect` = N > 0). The first N
// directions send emitters' light only; from direction N + 1 on reflected light is sent too. The
// estimate is then kept as two channels, summed apart: one-bounce (what emitters and the
// environment send, received once; the same fixed sender every direction) and multi-bounce (what
// reflecting surfaces send: direct + both estimates + glossy transfer). The one-bounce channel's
// sender is fixed, so it is the plain mean over all directions (unbiased at every n; j^k would
// only cost samples: Cornell box relMSE 2x lower at equal directions than the single j^k-weighted
// estimate, seed 1, 128-1024 directions); the multi-bounce channel is the j^k-weighted mean over
// its own directions (j from its first), so it forgets its first directions' missing bounces and
// the sum stays consistent: L = E + P + D + I with D = T E and I = T (P + D + I) (T the transport
// of one bounce, P point/spot light) is L = E + P + T L. With split channels the one-bounce
// estimate is light of two segments and goes to layer `direct`, the multi-bounce one to `rest`.
//
// Camera view. The mode's own raster (AtlasViewPass) gives each pixel its atlas uv, page and side;
// the shade pass adds the emission seen (G-buffer, front faces), the environment behind the scene
// and the reflected radiance of that texel side, bilinear between texel centres of the same chart.
// The atlas is view-independent: resolve() renders view_samples jittered samples per pixel of the
// current atlas (a box filter) into a fresh accumulator; nothing of earlier resolves is kept.
//
// Glossy lobes ([HHGM10] sections 5.3-5.4; `glossy` = transfer, interleaved transfer only). The
// atlas stays view-independent (Lambert); a glossy lobe is carried two ways. Glossy transfer atlas:
// a glossy texel side hit along direction i also stores what its lobe reflects of the same incoming
// light toward the one of +-omega_{i+1} on its side, pi weight L f_glossy / A_T per pixel (the
// Lambert estimator with rho / pi replaced by the lobe); the update adds it to the sender of
// direction i + 1 only. Averaged over directions this is an unbiased one-sample estimate of the
// lobe's outgoing radiance toward omega_{i+1} whenever omega_i is distributed independently of
// omega_{i+1} (hence every direction sequence is taken in a shuffled order within blocks:
// DirectionOrder.h),
// and it includes what reached the texel glossily at i - 1: paths through any number of glossy
// surfaces. Point/spot light reaches the glossy transfer atlas by the direct pass's
// sample points (their lobes toward omega_{i+1}). Final glossy gather toward the eye: per
// direction, a jittered camera G-buffer; each glossy pixel p takes the neighbour fragment of its
// bundle list along the direction on its side and adds L_sender f_glossy(p, d, eye) cos / p_r,
// weighted by w_j like the atlas; the point/spot lights' own highlight per view sample.
//
// Limits (the plan says so): textured albedo is taken per texel at its sample point, path-length
// layers are not separated (all reflected light is in layer `rest`; with delay_indirect the
// one-bounce estimate is in `direct`), glossy lobes need the
// interleaved transfer (bounce-by-bounce keeps their albedo only). Overflow: a direction whose bundle did not fit grows the pool and is built
// again; what the device cannot hold is refused with the numbers.
//
// Parameters (`bundlelab modes`):
//   atlas_resolution   512     texels     side of an atlas page (the density follows from the scene's area)
//   bundle_resolution  512     pixels     side of each direction's bundle (frame over the bounding sphere)
//   directions         halton             halton, random or stratified directions on the sphere
//   strata             1024    directions directions per pass of the stratified sequence
//   weighting          2                  k: direction j weighs j^k in the mean (0: plain mean)
//   view_samples       16      samples    jittered camera samples per pixel at resolve
//   bilinear           true               bilinear lookups between texel centres inside a chart
//   memory_cap_mib     0       MiB        node storage limit of the bundle pool (0: half the largest
//                                         device-local heap)
//   glossy             transfer           transfer (glossy transfer atlas + gather), gather (toward the
//                                         eye only), off (albedo only)
//   transfer           interleaved        interleaved (Gauss-Seidel) or bounce (one pass per bounce)
//   bounce_directions  256     directions transfer = bounce: directions per pass
//   max_segments       0       segments   transfer = bounce: longest path kept (0: no limit)
//   delay_indirect     0       directions N: the first N directions direct light only, one-bounce (plain
//                                         mean) and multi-bounce (j^k) estimates apart (0: one estimate;
//                                         interleaved only)
//   importance_offset  1.0                directions = importance: offset of the environment's density
//   shadow_resolution  512     texels     side of each point/spot light's shadow cube face
//   light_samples      2       per side   n x n points per texel gather point/spot light
//   first_shot         auto               the area emitters' and the environment's direct light shot
//                                         into the direct atlas (auto: where the settings allow it)
//   shot_samples       one                first shot: one light_samples point per texel and direction,
//                                         drawn by its area (all: the whole grid, light_samples^2 x the cost)
//   emitter_points     4       points     first shot: on the emitters per direction
//   emitter_shadow_resolution 256 texels  first shot: side of each point's shadow cube face
//   environment_shots  4       directions first shot: toward the environment per direction, by its
//                                         importance, a depth map each (0: the list ends carry it)
//   environment_shadow_resolution 512     first shot: side of each direction's depth map
#pragma once

#include "atlas/TexelRadiance.h"
#include "modes/EnvironmentShadowParameters.h"
#include "modes/Mode.h"
#include "modes/atlas/AtlasModeOptions.h"

#include <vulkan/vulkan.h>

#include <modes/atlas/AtlasShared.h>

#include <memory>
#include <optional>

namespace bl {

class AtlasMode final : public Mode {
public:
    static constexpr const char* kAtlasResolution = "atlas_resolution";
    static constexpr const char* kBundleResolution = "bundle_resolution";
    static constexpr const char* kDirections = "directions";
    static constexpr const char* kStrata = "strata";
    static constexpr const char* kImportanceOffset = "importance_offset";
    static constexpr const char* kWeighting = "weighting";
    static constexpr const char* kTransfer = "transfer";
    static constexpr const char* kBounceDirections = "bounce_directions";
    static constexpr const char* kMaxSegments = "max_segments";
    static constexpr const char* kViewSamples = "view_samples";
    static constexpr const char* kBilinear = "bilinear";
    static constexpr const char* kShadowResolution = "shadow_resolution";
    static constexpr const char* kLightSamples = "light_samples";
    static constexpr const char* kMemoryCap = "memory_cap_mib";
    static constexpr const char* kPoolNodes = "pool_nodes_per_pixel";
    static constexpr const char* kGlossy = "glossy";
    static constexpr const char* kDelayIndirect = "delay_indirect";
    static constexpr const char* kFirstShot = "first_shot";
    static constexpr const char* kShotSamples = "shot_samples";
    static constexpr const char* kEmitterPoints = "emitter_points";
    static constexpr const char* kEmitterShadowResolution = "emitter_shadow_resolution";
    static constexpr const char* kEnvironmentShots = kEnvironmentShotsKey;
    static constexpr const char* kEnvironmentShadowResolution = kEnvironmentShadowResolutionKey;

    // The ids of the plan's passes that setScene() and iterate() execute (AtlasPlan.cpp).
    static constexpr const char* kPassFirstShot = "first-shot";
    static constexpr const char* kPassDelayedIndirect = "delayed-indirect";
    static constexpr const char* kPassGlossyTransfer = "glossy-transfer";
    static constexpr const char* kPassGlossyGather = "glossy-gather";

    static std::vector<ParamSpec> parameters();
    static std::unique_ptr<Mode> create(const Settings& settings);

    explicit AtlasMode(const Settings& settings);
    ~AtlasMode() override;

    std::string_view name() const override { return "atlas"; }
    void setScene(const Scene& scene, vk::Context* gpu) override;
    void iterate(const IterationInfo& info) override;
    ImageSet resolve() override;
    const Settings& settings() const override { return mSettings; }
    PassTimes timings() const override;
    PassPlan plan(const Scene& scene) const override;
    // The exchange lives in the atlas; only the glossy gather (and its highlights) follows the eye.
    bool viewIndependent() const override { return mPlan.size() > 0 && !mPlan.runs(kPassGlossyGather); }
    TradeSettings trades() const override;

    // The reflected radiance of every texel side, weighted sum / total weight (rgb; index 2 * texel + side),
    // and the texels' emission: tests check the atlas itself (the furnace: every texel -> 2).
    struct TexelReadback {
        std::vector<glm::vec3> reflected;
        std::vector<glm::vec3> emission;
        std::vector<float> area; // preimage area of each texel, 0 where no surface maps
    };
    TexelReadback readTexels() const;
    // The same as texel sides of the atlas, to compare with the path tracer's bake of the same
    // texels (core/atlas/TexelRadiance.h, reference/TexelBaker.h); and that atlas's texel maps.
    atlas::TexelRadiance texelRadiance() const;
    const atlas::Atlas& atlas() const;
    const atlas::TexelMaps& texelMaps() const { return atlas().maps; }
    // The global direction omega of the i-th direction processed (its sequence and seed fixed by the
    // first iterate(), the order as the mode takes it): tests replay the mode's directions.
    glm::vec3 direction(std::uint32_t i) const;

private:
    struct Gpu;
    // The i-th direction's bundle frame (its direction and sub-pixel jitter, fixed by i and the seed).
    shader::BundleFrame bundleFrame(std::uint32_t i, std::uint64_t seed) const;
    // Records the reset, build and sort of the bundle for `frame` (slot 0).
    void recordBundle(VkCommandBuffer cmd, const shader::BundleFrame& frame, double time);
    // Makes this direction's bundle: kept from the previous direction's submission, which built it
    // at its end, or built now in a submission of its own (the first direction, after an overflow).
    void ensureBundle(const IterationInfo& info, const shader::BundleFrame& frame);
    // This direction's parameters for the exchange (the sender's left for iterate()).
    shader::AtlasDirection directionParams(const shader::BundleFrame& frame) const;
    // Point/spot lights at scene time `time` into the direct atlas and the first sender.
    void lightDirect(double time);
    void recordDirect(VkCommandBuffer cmd, const shader::AtlasDirectPush& push, const char* name, std::uint32_t count);
    shader::AtlasDirectPush glossyPush() const; // directPush() with the glossy passes' buffers
    // Glossy materials: point/spot lights into the glossy transfer atlas and the final glossy
    // gather after a direction's exchange (w_j = weight); the lights' highlight of a view sample.
    void recordGlossyLights(VkCommandBuffer cmd);
    shader::AtlasDirectPush directPush() const;
    void recordGather(VkCommandBuffer cmd, double weight);
    void recordHighlight(VkCommandBuffer cmd);
    // View samples recorded into one submission by resolve() (each takes four timer scopes).
    static constexpr std::uint32_t kViewSamplesPerSubmission = 8;
    // first_shot: the emitter points' pass and pipeline (set-up), and one iteration's shot: the
    // points' cubes and their light into the direct atlas and the senders' constant part
    // (AtlasFirstShot.cpp).
    void setUpFirstShot(const Scene& scene);
    // Whether the first shot runs on `scene` and, where not, why (plan). `conflict` names a setting
    // whose sender the shot's light would not reach (transfer = bounce, delay_indirect, glossy
    // transport): first_shot = auto then leaves the shot out, first_shot = on is refused.
    struct FirstShotChoice {
        bool runs = false;
        bool area = false;        // the area emitters' part (emitter points)
        bool environment = false; // the environment's part (environment_shots depth maps)
        std::string code; // the plan's reason code
        std::string why;
        std::string conflict;
    };
    FirstShotChoice firstShotChoice(const Scene& scene) const;
    void recordFirstShot(VkCommandBuffer cmd, double time);
    // The sampler index of the i-th direction processed (shuffled in blocks for the glossy
    // transfer, DirectionOrder.h; else i).
    std::uint32_t directionIndex(std::uint32_t i) const;
    Settings mSettings;
    AtlasModeOptions mOptions; // mSettings, typed, read once
    PassPlan mPlan;            // plan(scene) of the scene given to setScene: what iterate() runs
    const Scene* mScene = nullptr;
    vk::Context* mContext = nullptr;
    std::unique_ptr<Gpu> mGpu;
    std::uint32_t mIterations = 0;
    double mTotalWeight = 0.0; // sum of w_j over the directions in the sums (bounce: of the current pass)
    // delay_indirect > 0: the multi-bounce channel's directions so far and the sum of their weights.
    std::uint32_t mIndirectDirections = 0;
    double mIndirectWeight = 0.0;
    std::uint32_t mPass = 1;   // transfer = bounce: the pass (bounce) under way, 1-based
    double mTime = 0.0; // scene time of the last direction: the view renders the scene there
    std::uint64_t mSeed = 0; // run seed of the last direction: the view's pixel jitter follows it
    std::optional<double> mSolutionTime; // scene time of the geometry and lights the atlas holds
};

} // namespace bl
