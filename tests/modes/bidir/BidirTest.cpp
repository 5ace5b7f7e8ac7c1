// Mode bidir's estimators against the reference path tracer on the Cornell box lit by a point
// light: the one-bounce term ([TO12] Eq. 3-6) by each strategy alone converges to the reference's
// `indirect1` layer and MIS has lower error than either at equal samples; the two-bounce term
// (Eq. 7-8) converges to `indirect2` unclamped and loses a stated share of it clamped. The MIS
// runs use the mode's defaults (VPLs from reflective shadow maps, bundle frames fitted to the
// visible points); the VPL strategy's runs trace their VPLs (vpl_source = traced, the exact
// sampler the RSM is checked against), whose 1/r^2 tail the seeds bound to kNoisyTolerance per
// region.
//
// Statistics (tests/support/Statistics.h): S independent seeds per configuration, each F frames
// of K pairs. For each of R x R image regions, the seeds' region means give a mean and a standard
// error (the seeds' spread); the test asserts |mean - reference| <= tolerance + t stderr with
// Holm's correction over the regions, behind the noise gate stderr <= tolerance / 3 (else the
// test could not fail for the bias it allows). More seeds of fewer frames (8 x F/2 where it was
// 4 x F: the same samples, the same run time) buy a t quantile of 7 dof instead of 3.
//
// Run time: every configuration is rendered once per seed and cached for the whole suite; the
// equal-sample comparison reads the same runs at frame 128 (resolve() is non-destructive), and
// the two-bounce test reads the MIS run's `indirect2` layer.
#include "gpu/GpuScene.h"
#include "modes/Registry.h"
#include "modes/bidir/ReflectiveShadowMap.h"
#include "modes/bidir/VplSampler.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "scene/SceneLoader.h"
#include "scene/ShaderConversions.h"
#include "support/Statistics.h"
#include "support/TestFiles.h"
#include "support/TexturedScenes.h"
#include "support/VulkanTest.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <shared/Lights.h>

using namespace bl;
namespace stats = bl::test::stats;

namespace {

constexpr int kResolution = 32;        // camera pixels per side: the estimator, not the image, is tested
constexpr int kRegions = 4;            // R x R regions of 8 x 8 pixels
// Independent runs per configuration (stats::seeds(kSeeds): 1..12). Since the pixel jitter follows
// the seed (core/sampling/PixelSamples.h) the seeds' spread also holds the footprint's integration
// error, which 8 seeds left a few percent above the noise gate in some regions.
constexpr std::uint32_t kSeeds = 12;
constexpr std::uint32_t kFrames = 256; // frames per run of the single-strategy convergence tests
constexpr std::uint32_t kMisFrames = kFrames / 2;
constexpr std::uint32_t kFastFrames = 64; // frames per run of the defaults' fast tests (8 seeds: the MIS regions
// at 32 frames spread 1.7-2% of a region, above the noise gate of kTolerance)
// The spot-lit box's corners below the cone get 5-20% of the mean region's indirect light; at 64
// frames their relative spread reaches 7%, so the fast tests hold regions below this share of the
// mean region to the tolerance of that share (expectConverged).
constexpr double kDimRegion = 0.25;
// The floor view's two-bounce image mean at 64 frames: its right tail (single paths across the
// walls' corners) spreads the seeds by ~9% (4 seeds: +-4.5%, measured -1.2%); 10% still catches
// a fit that cuts hidden hits (-79%).
constexpr double kFloorViewTwoBounceTolerance = 0.10;
constexpr std::uint32_t kReferenceSpp = 1024;
constexpr const char* kRsm = "rsm_resolution=64"; // texels per RSM cube face side (vpl_source = rsm)
// Environment bundles' test: E bundles per frame, frames per seed (8 seeds: twice the directions
// of the 4 x 24 it had) and the tolerance of its regions and image mean. The sun's few directions
// give the lit regions a heavy tail: their standard error stays at 3.4% of a region at 8 x 24 and
// 8 x 32 frames alike (regions 0 and 7; the image mean's 1.25-1.5%), so the noise gate lets them
// resolve 3 x 3.4%: 12% (measured at 4 x 16: every region within -6.0%..+2.5%). Regions that see mostly sky (direct light below 5% of the mean region's) are left
// out of the region test: their relative error means nothing.
constexpr std::uint32_t kEnvironmentBundles = 8;
constexpr std::uint32_t kEnvironmentFrames = 24;
constexpr double kEnvironmentTolerance = 0.12;
// Frames per seed of the textured-albedo test.
constexpr std::uint32_t kTexturedFrames = 32;
const std::vector<std::string> kCommon = {"pairs_per_frame=8", "bundle_resolution=128", "shadow_resolution=256",
                                          "vpl_shadow_resolution=128", kRsm};

// Tolerance: shadow cubes (4x4 PCF) and bundle pixels move visibility boundaries by up to a texel
// or pixel, a few percent of a region near contact shadows; the reference's own error at 1024 spp
// over 64 pixels is below 1%.
constexpr double kTolerance = 0.05;
// The MIS runs' VPL cubes: at 128^2 the bottom-right floor region (the short block's contact
// shadow) loses 5.5 +- 0.3% under MIS (RSM or traced VPLs alike, 8 seeds x 512 frames), beyond the
// tolerance; at 256^2 (the mode's default) 3% of it comes back (seeds 1-2, 256 frames: 0.91 ->
// 0.94, 0.94 -> 0.97 of the reference; bundles at 256^2 change nothing).
constexpr const char* kMisVplCubes = "vpl_shadow_resolution=256";
// The single strategies alone and the unclamped two-bounce term (VPL strategy: the 1/r^2 tail;
// bundle strategy: small bright regions missed) spread their regions' seeds far more than MIS's
// one-bounce term: at 8 seeds x 256 frames (two-bounce: x 128) the standard error reaches 3.5% of
// a region (vpl region 14, bundle 12-13, two-bounce 8-9; MIS at most 1.4%), so the noise gate
// (stderr <= tolerance / 3) lets them resolve 10%, not kTolerance: they are held to 10% region by
// region (dim regions floored at kDimRegion), MIS's one-bounce regions to kTolerance, and every
// image mean to kImageTolerance.
constexpr double kNoisyTolerance = 0.10;
// The unclamped two-bounce term's regions under MIS (8 seeds x 128 frames) reach a standard error
// of 3.9% of the region (region 13, bottom row): the gate needs 3 x 3.9%.
constexpr double kTwoBounceTolerance = 0.12;
// RsmVplsConvergeRegionByRegion (MIS, bounces 1, 8 seeds x kFastFrames): the point light's region
// 12 spreads 1.74% of the region, the gate needs 3 x 1.74%.
constexpr double kRsmMisTolerance = 0.06;
// The image mean averages those boundary shifts out: measured -1% to -2% for all three strategies.
constexpr double kImageTolerance = 0.03;
// Frames of the equal-sample error comparison (read from the convergence runs).
constexpr std::uint32_t kComparisonFrames = 128;
// two_bounce_clamp of the clamped run (|x1 - x2| >= 0.1 of the scene radius) and the share of
// the reference's indirect2 it loses on this scene: measured 1.76 +- 0.06% (seeds 1.63-1.88%,
// 128 frames); the test brackets it by [1%, 3%].
constexpr const char* kClamp = "two_bounce_clamp=0.1";
constexpr std::uint32_t kClampFrames = kComparisonFrames; // paired with the unclamped runs' frame 128
constexpr double kClampLossMin = 0.01;
constexpr double kClampLossMax = 0.03;
// The glossy scene's test: frames per seed (its VPL cubes cost 4 ms each: 1,112 triangles x 6
// faces) and its tolerances. The 10% its regions had was widened for two ceiling regions at
// -9.3% / +7.0% under MIS that issue 19 (B3) suspected the VPL term's cosine cancellation on the
// sphere's smooth normals of: experiments/bidir-b3/ refutes that (the sphere flat or smooth moves
// vpl - bundle by <= 0.5% of a ceiling region; the strategies agree within 1.9 sigma everywhere),
// the offsets are biases both strategies share. What the noise supports instead: at 8 seeds x 32
// frames the regions' standard errors reach 2.6-4.4% of a region (the image mean's 1.5%), so 8 x
// 64 frames (1.8-3.1%) resolve kNoisyTolerance region by region (dim ceiling regions floored at
// kDimRegion); the one-bounce image mean (1.05% at 64 frames) kTolerance, the two-bounce image
// mean (1.7% at 64 frames) kNoisyTolerance.
constexpr std::uint32_t kGlossyFrames = 64;
constexpr double kGlossyTolerance = kNoisyTolerance;

Scene cornellPoint() {
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell-point.toml"));
    s.camera.resolution = {kResolution, kResolution};
    return s;
}

double counterOf(const ImageSet& out, const std::string& name) {
    for (const auto& [key, value] : out.counters) {
        if (key == name) return value;
    }
    ADD_FAILURE() << "no counter " << name;
    return -1.0;
}

// Mean of each channel over an image.
glm::dvec3 channelMeans(const Image& image) {
    glm::dvec3 sum(0.0);
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) sum += glm::dvec3(image.at(x, y));
    return sum / double(image.width() * image.height());
}

using stats::luminance;

// Mean luminance of each of the kRegions x kRegions regions of an image.
std::vector<double> regionMeans(const Image& image) { return stats::blockMeans(image, kResolution / kRegions); }

double imageMean(const std::vector<double>& regions) {
    double sum = 0.0;
    for (double v : regions) sum += v / double(regions.size());
    return sum;
}

// Per seed, the image mean (the regions are equal in area): its spread over seeds is the image's
// own, the regions of one run being correlated (one VPL lights them all).
std::vector<double> imageMeans(const std::vector<std::vector<double>>& perSeed) {
    std::vector<double> means;
    for (const auto& regions : perSeed) means.push_back(imageMean(regions));
    return means;
}

// Per seed, the squared error against the reference summed over the regions.
std::vector<double> squaredErrors(const std::vector<std::vector<double>>& perSeed, const std::vector<double>& reference) {
    std::vector<double> errors;
    for (const auto& regions : perSeed) {
        double e = 0.0;
        for (std::size_t i = 0; i < regions.size(); ++i) e += (regions[i] - reference[i]) * (regions[i] - reference[i]);
        errors.push_back(e);
    }
    return errors;
}

// The image mean alone (for layers whose regions the seeds cannot bound) within `tolerance` of the
// reference's, behind the noise gate (stats::agrees).
void expectImageMeanConverged(const std::vector<std::vector<double>>& perSeed, const std::vector<double>& reference,
                              const std::string& name, double tolerance) {
    const stats::Summary s = stats::summarize(imageMeans(perSeed));
    const double ref = imageMean(reference);
    std::printf("%s: image mean %.5f reference %.5f (%+.2f%%) +- %.2f%%\n", name.c_str(), s.mean, ref,
                100.0 * (s.mean / ref - 1.0), 100.0 * s.stderr_ / ref);
    EXPECT_TRUE(stats::agrees(s, ref, tolerance * ref, name + " image mean"));
}

// Every region within `tolerance` (relative) of the reference, Holm-corrected over the regions,
// behind the noise gate (stats::regionsAgree); regions dimmer than `floor` times the mean region
// are held to `tolerance` of that floor (a region with 5% of the mean's light matters as much to
// the image at 5% error as the mean region at 0.25%). And the image mean within `imageTolerance`.
void expectConverged(const std::vector<std::vector<double>>& perSeed, const std::vector<double>& reference,
                     double tolerance, const std::string& name, double floor = 0.0,
                     double imageTolerance = kImageTolerance) {
    EXPECT_TRUE(stats::regionsAgree(perSeed, reference, {tolerance, floor, stats::kAlpha}, name));
    expectImageMeanConverged(perSeed, reference, name, imageTolerance);
}

// One configuration's runs: per seed, the region means of indirect1 and indirect2 at
// kComparisonFrames and at the end.
struct Runs {
    std::vector<std::vector<double>> early1, early2, final1, final2;
};

class Bidir : public bl::test::VulkanTest {
protected:
    static void SetUpTestSuite() {
        ImageSet ref = bl::test::renderReference(cornellPoint(), kReferenceSpp);
        reference1 = regionMeans(bl::test::layerOf(ref, "indirect1"));
        reference2 = regionMeans(bl::test::layerOf(ref, "indirect2"));
    }
    static void TearDownTestSuite() { cache.clear(); }

    // The runs of one configuration on the point-lit box, rendered on first use.
    const Runs& runs(const std::vector<std::string>& extra, std::uint32_t frames) {
        std::string key = std::to_string(frames);
        for (const std::string& e : extra) key += " " + e;
        auto it = cache.find(key);
        if (it != cache.end()) {
            return it->second;
        }
        return cache.emplace(key, renderSeeds(cornellPoint(), extra, frames)).first->second;
    }

    // Per seed, the region means of indirect1 and indirect2 of scene `s` at kComparisonFrames
    // (early1, early2, when reached) and after `frames` frames (final1, final2).
    Runs renderSeeds(const Scene& s, const std::vector<std::string>& extra, std::uint32_t frames) {
        Runs r;
        for (std::uint32_t seed : stats::seeds(kSeeds)) {
            std::vector<std::string> settings = kCommon;
            settings.insert(settings.end(), extra.begin(), extra.end());
            std::unique_ptr<Mode> mode = createMode("bidir", settings);
            mode->setScene(s, &ctx());
            for (std::uint32_t f = 0; f < frames; ++f) {
                mode->iterate({f, seed, 0.0});
                if (f + 1 == kComparisonFrames) {
                    ImageSet early = mode->resolve();
                    r.early1.push_back(regionMeans(bl::test::layerOf(early, "indirect1")));
                    r.early2.push_back(regionMeans(bl::test::layerOf(early, "indirect2")));
                }
            }
            ImageSet out = mode->resolve();
            EXPECT_EQ(out.nonFiniteSamples, 0u);
            // Every camera point falls inside every bundle (fit = scene or visible): a point
            // outside one would drop its pixel's sample.
            EXPECT_EQ(counterOf(out, "dropped_samples"), 0.0);
            // An RSM's VPL whose direction left its texel (the rasterizer's sample at the texel's
            // edge; measured 2 of 4096 in one seed): rare, its density taken at its direction.
            for (const auto& [name, value] : out.counters) {
                if (name == "rsm_texel_mismatches") {
                    EXPECT_LE(value, 1e-3 * frames * 8);
                }
            }
            r.final1.push_back(regionMeans(bl::test::layerOf(out, "indirect1")));
            r.final2.push_back(regionMeans(bl::test::layerOf(out, "indirect2")));
        }
        return r;
    }

    // The three one-bounce configurations; the single strategies run without the two-bounce
    // term (no bundles for vpl, no VPLs for bundle), MIS with it and otherwise the defaults
    // (vpl_source = rsm, fit = visible). The VPL strategy traces its VPLs: the RSM's VPL strategy
    // alone is tested in its image mean and, region by region, under MIS (RsmVpls... below).
    const Runs& vplRuns() { return runs({"strategy=vpl", "bounces=1", "vpl_source=traced"}, kFrames); }
    const Runs& bundleRuns() { return runs({"strategy=bundle", "bounces=1", "fit=visible"}, kFrames); }
    const Runs& misRuns() { return runs({"strategy=mis", "bounces=2", kMisVplCubes}, kMisFrames); }

    static std::vector<double> reference1, reference2;
    static std::map<std::string, Runs> cache;
};
std::vector<double> Bidir::reference1, Bidir::reference2;
std::map<std::string, Runs> Bidir::cache;

} // namespace

TEST_F(Bidir, VplStrategyConvergesToReferenceIndirect1) {
    expectConverged(vplRuns().final1, reference1, kNoisyTolerance, "vpl", kDimRegion);
}

TEST_F(Bidir, BundleStrategyConvergesToReferenceIndirect1) {
    expectConverged(bundleRuns().final1, reference1, kNoisyTolerance, "bundle", kDimRegion);
}

// VPLs from reflective shadow cubes on the GPU (vpl_source = rsm, 64^2 per face, jittered every
// frame): the VPL strategy's image mean converges to the reference's indirect1 (a wrong density,
// e.g. without the texel's Jacobian J / A, moves it by tens of percent). Region by region the VPL
// strategy alone carries a 1/r^2 tail few seeds cannot bound (8 seeds x 512 frames: every region
// within -5.5%..+2.5% of the reference, one region's seeds' spread 5.8%); RsmVplsConvergeRegionByRegion
// tests the RSM's VPLs region by region under MIS, see papers/tokuyoshi-ogaki-2012.md.
TEST_F(Bidir, RsmVplStrategyImageMeanConvergesToReferenceIndirect1) {
    const Runs& r = runs({"strategy=vpl", "bounces=1", "vpl_source=rsm"}, kComparisonFrames);
    expectImageMeanConverged(r.final1, reference1, "rsm vpl, 128 frames", kImageTolerance);
}

TEST_F(Bidir, MisConvergesToReferenceIndirect1) {
    expectConverged(misRuns().final1, reference1, kTolerance, "mis");
}

// MIS at equal samples (the same seeds, frames and pairs) has less error than either strategy
// alone (Fig. 4's point: VPLs spike near corners, bundles miss small bright regions; MIS neither).
// (The MIS runs' VPL cubes are finer, kMisVplCubes: at 128^2 too MIS had 1.1e-5 against 3.0e-5
// and 3.5e-5.)
TEST_F(Bidir, MisHasLowerErrorThanEitherStrategy) {
    const double mis = stats::summarize(squaredErrors(misRuns().early1, reference1)).mean;
    const double vpl = stats::summarize(squaredErrors(vplRuns().early1, reference1)).mean;
    const double bundle = stats::summarize(squaredErrors(bundleRuns().early1, reference1)).mean;
    std::printf("summed squared region error at %u frames: mis %.3g, vpl %.3g, bundle %.3g\n", kComparisonFrames, mis,
                vpl, bundle);
    EXPECT_LT(mis, vpl);
    EXPECT_LT(mis, bundle);
}

// The unclamped two-bounce term (one VPL, one bundle hit, the VPL's shadow cube between them)
// converges to the reference's indirect2 layer, region by region with kTwoBounceTolerance.
TEST_F(Bidir, TwoBounceUnclampedConvergesToReferenceIndirect2) {
    expectConverged(misRuns().final2, reference2, kTwoBounceTolerance, "two-bounce", kDimRegion);
}

// Clamping |x1 - x2| to 0.1 of the scene radius is a bias: the energy it loses is the difference
// to the unclamped runs with the same seeds and frames (paired: the same VPLs and bundles, so the
// difference is the clamp's alone, not noise), stated as a share of the reference's indirect2.
// One-bounce light is untouched by it.
TEST_F(Bidir, TwoBounceClampingLosesAStatedShare) {
    const Runs& clamped = runs({"strategy=mis", "bounces=2", kMisVplCubes, kClamp}, kClampFrames);
    const Runs& unclamped = misRuns();
    const double ref = imageMean(reference2);
    std::vector<double> losses, biases;
    for (std::uint32_t s = 0; s < kSeeds; ++s) {
        losses.push_back((imageMean(unclamped.early2[s]) - imageMean(clamped.final2[s])) / ref);
        biases.push_back(imageMean(clamped.final2[s]) / ref - 1.0);
        std::printf("seed %u: clamping loses %.2f%% of indirect2\n", s + 1, 100.0 * losses.back());
        EXPECT_EQ(clamped.final1[s], unclamped.early1[s]) << "seed " << s << ": one-bounce changed";
    }
    const stats::Summary loss = stats::summarize(losses);
    std::printf("two-bounce clamped (%s): loses %.2f%% +- %.2f%% of the reference's indirect2; clamped image mean "
                "%+.2f%% against it (%u frames)\n",
                kClamp, 100.0 * loss.mean, 100.0 * loss.stderr_, 100.0 * stats::summarize(biases).mean, kClampFrames);
    // The bracket as a tolerance about its centre (paired: the gate sees the clamp's own spread).
    const double centre = 0.5 * (kClampLossMin + kClampLossMax), halfWidth = 0.5 * (kClampLossMax - kClampLossMin);
    EXPECT_TRUE(stats::agrees(loss, centre, halfWidth, "two-bounce clamping's loss"));
}

// Glossy suppression = none is unbiased on a glossy scene (McGuire's CornellBox-Glossy with exact
// Phong lobes, point light): indirect1 by regions and image mean, indirect2 by its image mean
// (its regions spread -8%..+17% at 128 frames, the ceiling's above the reference by more than the
// seeds' spread: not explained yet, see papers/tokuyoshi-ogaki-2012.md), MIS with the two-bounce
// term. (clamp and roughness are biases by design; their
// relMSE and energy lost are measured in experiments/bidir-glossy.toml.)
TEST_F(Bidir, NoSuppressionIsUnbiasedOnGlossyScene) {
    Scene s = loadScene(bl::test::sourcePath("data/external/cornell-glossy-point.toml"));
    s.camera.resolution = {kResolution, kResolution};
    const ImageSet glossyRef = bl::test::renderReference(s, kReferenceSpp);
    const std::vector<double> glossy1 = regionMeans(bl::test::layerOf(glossyRef, "indirect1"));
    const std::vector<double> glossy2 = regionMeans(bl::test::layerOf(glossyRef, "indirect2"));
    std::vector<std::vector<double>> perSeed1, perSeed2;
    for (std::uint32_t seed : stats::seeds(kSeeds)) {
        std::vector<std::string> settings = kCommon;
        settings.insert(settings.end(), {"strategy=mis", "bounces=2", "suppression=none"});
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < kGlossyFrames; ++f) mode->iterate({f, seed, 0.0});
        ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        perSeed1.push_back(regionMeans(bl::test::layerOf(out, "indirect1")));
        perSeed2.push_back(regionMeans(bl::test::layerOf(out, "indirect2")));
    }
    expectConverged(perSeed1, glossy1, kGlossyTolerance, "glossy one-bounce", kDimRegion, kTolerance);
    expectImageMeanConverged(perSeed2, glossy2, "glossy two-bounce", kNoisyTolerance);
}

// The pass plan skips glossy suppression on a scene without glossy materials, and the image is
// the same to the bit as with suppression = none; on the glossy scene it runs and changes the
// image (so the comparison can fail).
TEST_F(Bidir, PlanSkipsSuppressionWithoutGlossyMaterialImageUnchanged) {
    auto render = [&](const Scene& s, const std::string& suppression, bool expectRuns) {
        std::vector<std::string> settings = kCommon;
        settings.insert(settings.end(), {"strategy=mis", "bounces=2", "suppression=" + suppression});
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        bool listed = false;
        for (const PlannedPass& p : mode->plan(s)) {
            if (p.name.rfind("glossy suppression", 0) == 0) {
                listed = true;
                EXPECT_EQ(p.runs, expectRuns) << suppression << ": " << p.reason;
                std::printf("%s: %s\n", p.name.c_str(), p.reason.c_str());
            }
        }
        EXPECT_TRUE(listed);
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < 4; ++f) mode->iterate({f, 7, 0.0});
        ImageSet out = mode->resolve();
        return std::make_pair(bl::test::layerOf(out, "indirect1"), bl::test::layerOf(out, "indirect2"));
    };
    auto same = [](const Image& a, const Image& b) {
        for (int y = 0; y < kResolution; ++y)
            for (int x = 0; x < kResolution; ++x)
                if (a.at(x, y) != b.at(x, y)) return false;
        return true;
    };
    const Scene diffuse = cornellPoint();
    const auto skipped = render(diffuse, "roughness", false);
    const auto none = render(diffuse, "none", false);
    EXPECT_TRUE(same(skipped.first, none.first) && same(skipped.second, none.second));

    Scene glossy = loadScene(bl::test::sourcePath("data/external/cornell-glossy-point.toml"));
    glossy.camera.resolution = {kResolution, kResolution};
    const auto suppressed = render(glossy, "roughness", true);
    const auto glossyNone = render(glossy, "none", false);
    EXPECT_FALSE(same(suppressed.first, glossyNone.first));
}

// vpl_shadow_taps (specialization constant) changes only the filter of the two VPL-cube lookups:
// `direct` (the lights' cubes, 4x4 PCF) is the same to the bit, indirect light changes (the taps
// are applied) by no more than a filter's worth, and no sample is non-finite at 1, 2 or 3 taps.
TEST_F(Bidir, VplShadowTapsChangeOnlyTheVplShadowFilter) {
    const Scene s = cornellPoint();
    auto render = [&](int taps) {
        std::vector<std::string> settings = kCommon;
        settings.insert(settings.end(), {"strategy=mis", "bounces=2", "vpl_shadow_taps=" + std::to_string(taps)});
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < 8; ++f) mode->iterate({f, 3, 0.0});
        ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u) << taps << " taps";
        return out;
    };
    const ImageSet four = render(4);
    const double four1 = channelMeans(bl::test::layerOf(four, "indirect1")).y;
    const double four2 = channelMeans(bl::test::layerOf(four, "indirect2")).y;
    ASSERT_GT(four1, 0.0);
    for (int taps : {1, 2, 3}) {
        const ImageSet out = render(taps);
        const Image& direct = bl::test::layerOf(out, "direct");
        const Image& directFour = bl::test::layerOf(four, "direct");
        bool sameDirect = true, changed = false;
        const Image& ind = bl::test::layerOf(out, "indirect1");
        const Image& indFour = bl::test::layerOf(four, "indirect1");
        for (int y = 0; y < kResolution; ++y) {
            for (int x = 0; x < kResolution; ++x) {
                sameDirect = sameDirect && direct.at(x, y) == directFour.at(x, y);
                changed = changed || ind.at(x, y) != indFour.at(x, y);
            }
        }
        const double r1 = channelMeans(ind).y / four1;
        const double r2 = channelMeans(bl::test::layerOf(out, "indirect2")).y / four2;
        std::printf("vpl_shadow_taps %d / 4: indirect1 %.4f, indirect2 %.4f\n", taps, r1, r2);
        EXPECT_TRUE(sameDirect) << taps << " taps";
        EXPECT_TRUE(changed) << taps << " taps: the VPL lookups ignore the setting";
        EXPECT_NEAR(r1, 1.0, 0.02) << taps << " taps";
        EXPECT_NEAR(r2, 1.0, 0.04) << taps << " taps";
    }
}

// A scene without point or spot lights (the area-lit Cornell box): no VPLs, no bundles, no pool
// bound; every strategy renders the emitters and nothing else (it read the unbound pool's
// address 0 and crashed the device before), as the plan says.
TEST_F(Bidir, SceneWithoutPointLightsRendersEmittersOnly) {
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    s.camera.resolution = {16, 16};
    for (const char* strategy : {"vpl", "bundle", "mis"}) {
        std::unique_ptr<Mode> mode = createMode("bidir", {std::string("strategy=") + strategy, "pairs_per_frame=2"});
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < 2; ++f) mode->iterate({f, 1, 0.0});
        ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        double emitted = 0.0, rest = 0.0;
        for (int y = 0; y < 16; ++y) {
            for (int x = 0; x < 16; ++x) {
                emitted += luminance(bl::test::layerOf(out, "emitted").at(x, y));
                for (const char* layer : {"direct", "indirect1", "indirect2"}) {
                    rest += luminance(bl::test::layerOf(out, layer).at(x, y));
                }
            }
        }
        EXPECT_GT(emitted, 0.0) << strategy;
        EXPECT_EQ(rest, 0.0) << strategy;
    }
}

// Bundle frames fitted to the points the G-buffer sees ([TO12s] B.1) drop no sample (every camera
// point falls inside every bundle, jittered G-buffer included) and use smaller pixels than the
// scene's sphere for the same bundle_resolution; the convergence tests run with this fit (the
// default), VisibleFitFindsHitsBeyondTheVisiblePoints with hits no camera point sees.
TEST_F(Bidir, VisibleFitCoversEveryCameraPointWithSmallerPixels) {
    double effective[2] = {0.0, 0.0};
    const Scene s = cornellPoint();
    for (const char* fit : {"scene", "visible"}) {
        std::vector<std::string> settings = kCommon;
        settings.insert(settings.end(), {"strategy=bundle", "bounces=1", std::string("fit=") + fit});
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < 8; ++f) mode->iterate({f, 3, 0.0});
        ImageSet out = mode->resolve();
        EXPECT_EQ(counterOf(out, "dropped_samples"), 0.0) << fit;
        effective[fit[0] == 'v'] = counterOf(out, "bundle_effective_resolution");
    }
    std::printf("effective bundle resolution: scene %.1f, visible %.1f\n", effective[0], effective[1]);
    EXPECT_DOUBLE_EQ(effective[0], 128.0);
    EXPECT_GT(effective[1], 128.0);
}

// Direct environment light by environment bundles ([TO12] section 3, Eq. 2 importance directions):
// on the sky-blocks scene (no point light: no pairs) the `direct` layer converges to the
// reference's region by region and in its image mean, no sample dropped; with
// environment_bundles = 0 the plan skips the pass and `direct` is zero.
TEST_F(Bidir, EnvironmentBundlesConvergeToReferenceDirect) {
    Scene s = loadScene(bl::test::sourcePath("data/analytic/sky-blocks.toml"));
    s.camera.resolution = {kResolution, kResolution};
    const std::vector<double> reference = regionMeans(bl::test::layerOf(bl::test::renderReference(s, kReferenceSpp), "direct"));
    std::vector<std::vector<double>> perSeed;
    for (std::uint32_t seed : stats::seeds(kSeeds)) {
        std::vector<std::string> settings = kCommon;
        settings.push_back("environment_bundles=" + std::to_string(kEnvironmentBundles));
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        for (const PlannedPass& p : mode->plan(s)) {
            if (p.name == "environment bundles") {
                EXPECT_TRUE(p.runs) << p.reason;
            }
        }
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < kEnvironmentFrames; ++f) mode->iterate({f, seed, 0.0});
        ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        EXPECT_EQ(counterOf(out, "dropped_samples"), 0.0);
        perSeed.push_back(regionMeans(bl::test::layerOf(out, "direct")));
    }
    // Regions that see mostly sky (direct light below 5% of the mean region's) left out of the
    // region test; the image mean keeps them.
    double meanRegion = 0.0;
    for (double r : reference) meanRegion += r / double(reference.size());
    std::vector<double> litReference;
    std::vector<std::vector<double>> litPerSeed(perSeed.size());
    for (std::size_t i = 0; i < reference.size(); ++i) {
        if (reference[i] < 0.05 * meanRegion) continue;
        litReference.push_back(reference[i]);
        for (std::size_t k = 0; k < perSeed.size(); ++k) litPerSeed[k].push_back(perSeed[k][i]);
    }
    EXPECT_TRUE(stats::regionsAgree(litPerSeed, litReference, {kEnvironmentTolerance, 0.0, stats::kAlpha},
                                    "environment direct (lit regions)"));
    expectImageMeanConverged(perSeed, reference, "environment direct", kEnvironmentTolerance);

    std::unique_ptr<Mode> off = createMode("bidir", {"environment_bundles=0", "pairs_per_frame=2"});
    for (const PlannedPass& p : off->plan(s)) {
        if (p.name == "environment bundles") {
            EXPECT_FALSE(p.runs) << p.reason;
        }
    }
    off->setScene(s, &ctx());
    off->iterate({0, 1, 0.0});
    double direct = 0.0;
    const Image image = bl::test::layerOf(off->resolve(), "direct");
    for (int y = 0; y < kResolution; ++y)
        for (int x = 0; x < kResolution; ++x) direct += luminance(image.at(x, y));
    EXPECT_EQ(direct, 0.0);
}

// Textured albedo at bundle hits (the payload's UV in the packed texture buffer) and at RSM VPLs
// (the RSM's G-buffer): the point-lit box with a red/green floor, whose untextured white would put
// indirect1's blue channel far off (+17% for multibounce's same scene). What the texture changes is
// the balance of the channels: per seed each channel's share of indirect1's channel sum against the
// reference's (the VPLs' and bundles' noise, which all channels of a run share, cancels in the
// shares: 8 seeds x 32 frames put the channels' own means at 1.4% (bundle) to 4.8% (RSM VPLs)
// standard error, too noisy for kImageTolerance; their overall level is the untextured tests' job).
// The shares spread less: 0.4-1.0% (bundle) and 1.0-1.3% (RSM VPLs) standard error at 8 x 32, so
// they are held to kTolerance (the gate needs 3 x 1.3%), a third of what the missing texture does.
TEST_F(Bidir, TexturedAlbedoAtBundleHitsAndRsmVpls) {
    Scene s = cornellPoint();
    ASSERT_TRUE(bl::test::texturePlanar(s, "floor", bl::test::redGreenTexture()));
    const ImageSet ref = bl::test::renderReference(s, kReferenceSpp);
    const glm::dvec3 reference = channelMeans(bl::test::layerOf(ref, "indirect1"));
    for (const std::vector<std::string>& extra :
         {std::vector<std::string>{"strategy=bundle", "bounces=1"},
          std::vector<std::string>{"strategy=vpl", "bounces=1", "vpl_source=rsm"}}) {
        std::vector<double> channels[3];
        for (std::uint32_t seed : stats::seeds(kSeeds)) {
            std::vector<std::string> settings = kCommon;
            settings.insert(settings.end(), extra.begin(), extra.end());
            std::unique_ptr<Mode> mode = createMode("bidir", settings);
            mode->setScene(s, &ctx());
            for (std::uint32_t f = 0; f < kTexturedFrames; ++f) mode->iterate({f, seed, 0.0});
            const glm::dvec3 m = channelMeans(bl::test::layerOf(mode->resolve(), "indirect1"));
            for (int c = 0; c < 3; ++c) channels[c].push_back(m[c]);
        }
        const double referenceSum = reference.x + reference.y + reference.z;
        for (int c = 0; c < 3; ++c) {
            std::vector<double> shares;
            for (std::size_t k = 0; k < channels[c].size(); ++k) {
                shares.push_back(channels[c][k] / (channels[0][k] + channels[1][k] + channels[2][k]));
            }
            const stats::Summary sc = stats::summarize(shares);
            const double share = reference[c] / referenceSum;
            std::printf("%s: indirect1 channel %d share %.5f +- %.5f reference %.5f (%+.2f%%)\n", extra[0].c_str(), c,
                        sc.mean, sc.stderr_, share, 100.0 * (sc.mean / share - 1.0));
            EXPECT_TRUE(stats::agrees(sc, share, kTolerance * share, extra[0] + " indirect1 channel share " +
                                                                         std::to_string(c)));
        }
    }
}

// The RSM's VPLs (vpl_source = rsm) against traced ones (CPU rays, Embree: an independent sampler
// with an exact first hit): both estimate the same integral at fixed floor points x, the one-bounce
// light from every directly lit surface without the visibility y - x,
//   E[ I(omega) f_y f_x cos_y cos_x / (|y - x|^2 p_e(omega) P(l)) ],
// so any error in the RSM's VPL positions, normals, p_e or intensity shows, and nothing of the
// rendering does. 262,144 VPLs of each source; a point light (p_e near uniform) and a spot light
// with a 20-degree smooth edge (the RSM's p_e follows I(omega), the traced one is uniform in the
// cone: different densities, the same expectation).
TEST_F(Bidir, RsmVplsEstimateWhatTracedVplsEstimate) {
    constexpr std::uint32_t kCount = 4096, kRounds = 64;
    for (const bool spot : {false, true}) {
        Scene s = cornellPoint();
        if (spot) {
            s.lights[0].type = Light::Type::Spot;
            s.lights[0].direction = glm::normalize(glm::vec3(0.2f, -1.0f, -0.3f));
            s.lights[0].coneAngleDegrees = 50.0f;
            s.lights[0].falloffDegrees = 20.0f;
        }
        gpu::GpuScene gpuScene(ctx(), s);
        ReflectiveShadowMap rsm(ctx(), gpuScene, 64);
        VplSampler traced(s);
        for (const glm::vec3 x : {glm::vec3(278.0f, 0.5f, 60.0f), glm::vec3(100.0f, 0.5f, 100.0f),
                                  glm::vec3(450.0f, 0.5f, 30.0f)}) {
            double sum[2] = {0.0, 0.0}, sum2[2] = {0.0, 0.0};
            for (std::uint32_t r = 0; r < kRounds; ++r) {
                const std::vector<shader::BidirVpl> vpls[2] = {rsm.sample(std::uint64_t(r) * kCount, kCount, 9, 0.0, 0.01f, nullptr),
                                                               traced.sample(std::uint64_t(r) * kCount, kCount, 9, 0.0, 0.01f)};
                for (int source = 0; source < 2; ++source) {
                    for (const shader::BidirVpl& v : vpls[source]) {
                        const glm::vec3 d = x - v.position;
                        const float r2 = glm::dot(d, d);
                        const glm::vec3 w = d / std::sqrt(r2);
                        const float cosY = glm::dot(v.normal, w), cosX = -w.y; // the floor faces +y
                        if (!v.valid || cosY <= 0.0f || cosX <= 0.0f) continue;
                        const double c = luminance(v.intensity * v.albedo) * cosY * cosX / (r2 * v.pdfLight);
                        sum[source] += c;
                        sum2[source] += c * c;
                    }
                }
            }
            const double n = double(kCount) * kRounds;
            double mean[2], sigma[2];
            for (int source = 0; source < 2; ++source) {
                mean[source] = sum[source] / n;
                sigma[source] = std::sqrt(std::max(0.0, sum2[source] / n - mean[source] * mean[source]) / n);
            }
            const double combined = std::hypot(sigma[0], sigma[1]);
            std::printf("%s light, x (%.0f %.0f %.0f): rsm %.5g +- %.2g, traced %.5g +- %.2g (%+.2f%%, %+.1f sigma)\n",
                        spot ? "spot" : "point", x.x, x.y, x.z, mean[0], sigma[0], mean[1], sigma[1],
                        100.0 * (mean[0] / mean[1] - 1.0), (mean[0] - mean[1]) / combined);
            EXPECT_LT(combined, 0.02 * mean[1]) << "too noisy to test";
            EXPECT_NEAR(mean[0], mean[1], 4.0 * combined) << (spot ? "spot" : "point");
        }
    }
}


// Traced VPLs of a spot light leave it with p_e = I(omega) / integral(I) ([TO12] 4.1; VplSampler's
// inversion of the profile's CDF, blBidirEmissionPdf), checked against the profile itself
// (blLightProfile integrated by the midpoint rule over cos(theta), not the sampler's closed form):
// the share of rays in each band of cos(theta) about the axis is the band's share of the
// integral (the inner cone, and the smoothstep ring in four parts; binomial errors), and I / p_e
// is the whole integral for every ray. A spot pointing down with a 25-degree cone meets the floor
// everywhere (no ray escapes). 65,536 rays, well under a second.
TEST_F(Bidir, TracedSpotVplsFollowTheProfile) {
    Scene s = cornellPoint();
    s.lights[0].type = Light::Type::Spot;
    s.lights[0].direction = glm::vec3(0.0f, -1.0f, 0.0f);
    s.lights[0].coneAngleDegrees = 25.0f;
    s.lights[0].falloffDegrees = 15.0f;
    const shader::GpuLight light = toGpuLight(s.lights[0]);
    // Integral of the profile over cos in (lo, hi] (times 2 pi: over the solid angle of the band).
    auto integral = [&](double lo, double hi) {
        constexpr int kSteps = 200000;
        double sum = 0.0;
        for (int i = 0; i < kSteps; ++i) {
            const double c = lo + (hi - lo) * (i + 0.5) / kSteps;
            const double sine = std::sqrt(std::max(0.0, 1.0 - c * c));
            sum += shader::blLightProfile(light, glm::vec3(float(sine), float(-c), 0.0f));
        }
        return 2.0 * 3.14159265358979 * sum * (hi - lo) / kSteps;
    };
    VplSampler traced(s);
    constexpr std::uint32_t kCount = 65536;
    const std::vector<shader::BidirVpl> vpls = traced.sample(0, kCount, 5, 0.0, 0.01f);
    const double cosInner = light.cosInner, cosOuter = light.cosOuter;
    std::vector<double> edges = {1.0, cosInner};
    for (int i = 1; i <= 4; ++i) edges.push_back(cosInner + (cosOuter - cosInner) * i / 4.0);
    std::vector<double> count(edges.size() - 1, 0.0);
    const double total = integral(cosOuter, 1.0);
    double worst = 0.0;
    for (const shader::BidirVpl& v : vpls) {
        ASSERT_EQ(v.valid, 1u);
        const glm::vec3 omega = -v.toLight;
        const double c = glm::dot(omega, light.direction);
        const double ratio = shader::blLightProfile(light, omega) / v.pdfLight / total;
        worst = std::max(worst, std::abs(ratio - 1.0));
        for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
            if (c <= edges[b] && c > edges[b + 1]) count[b] += 1.0;
        }
    }
    for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
        const double p = integral(edges[b + 1], edges[b]) / total;
        const double share = count[b] / kCount;
        const double sigma = std::sqrt(p * (1.0 - p) / kCount);
        std::printf("spot band cos (%.4f, %.4f]: share %.5f, expected %.5f +- %.5f (%+.1f sigma)\n", edges[b + 1],
                    edges[b], share, p, sigma, (share - p) / sigma);
        EXPECT_NEAR(share, p, 4.0 * sigma) << "band " << b;
    }
    // p_e proportional to I: I / p_e is the profile's integral for every ray (float precision).
    std::printf("spot: largest |I / (p_e integral) - 1| %.2g\n", worst);
    EXPECT_LT(worst, 1e-4) << "p_e not I / integral(I)";
}

namespace {
// The point-lit box with its light turned into a spot toward the red wall's foot (40-degree cone,
// 15-degree smooth edge): most of the box is lit only indirectly.
Scene cornellSpot() {
    Scene s = cornellPoint();
    s.lights[0].type = Light::Type::Spot;
    s.lights[0].direction = glm::normalize(glm::vec3(-0.4f, -1.0f, 0.15f));
    s.lights[0].coneAngleDegrees = 40.0f;
    s.lights[0].falloffDegrees = 15.0f;
    return s;
}
} // namespace

// VPLs from reflective shadow cubes (vpl_source = rsm, the default) against the reference, region
// by region, on the point-lit box and on the spot-lit one (the RSM's p_e follows the profile):
// MIS with bounces = 1, whose balance heuristic bounds the VPL term's 1/r^2 near corners (the VPL
// strategy alone has a tail that a few seeds cannot bound, see RsmVplStrategyImageMean...), so a
// wrong VPL position, normal, albedo, intensity or density shows in its region. 8 seeds x 64
// frames per light, regions within kRsmMisTolerance.
TEST_F(Bidir, RsmVplsConvergeRegionByRegion) {
    for (const bool spot : {false, true}) {
        const Scene s = spot ? cornellSpot() : cornellPoint();
        const std::vector<double> reference = regionMeans(bl::test::layerOf(bl::test::renderReference(s, kReferenceSpp), "indirect1"));
        const Runs r = renderSeeds(s, {"strategy=mis", "bounces=1", "vpl_source=rsm", kMisVplCubes}, kFastFrames);
        expectConverged(r.final1, reference, kRsmMisTolerance, spot ? "rsm mis, spot" : "rsm mis, point",
                        kDimRegion);
    }
}

// Bundle frames fitted to the visible points (fit = visible, the default) must still find every
// surface along a visible point's ray, not only visible ones: the camera looks straight down at the
// floor and the blocks' tops, so a bundle's next vertex y is almost always a wall, the ceiling or
// a block's side, none of them seen. MIS with the two-bounce term (whose second vertex is that
// hit): indirect1 converges to the reference region by region, indirect2 in the image mean (its
// regions carry the unclamped term's 1/r^2 tail). 8 seeds x 64 frames; the walls' regions seen at
// grazing angles spread their seeds by 3.5% at 32 frames (2.5% at 64), so the regions are held to
// kNoisyTolerance, and so is the image mean (1.7% standard error at 64 frames), ample for the
// mutation this test is for: the bundles' depth range fitted to the visible points too (indirect1
// -24.8%, indirect2 -78.6%).
TEST_F(Bidir, VisibleFitFindsHitsBeyondTheVisiblePoints) {
    Scene s = cornellPoint();
    s.camera.pose.position = glm::vec3(278.0f, 540.0f, 279.5f);
    s.camera.pose.target = glm::vec3(278.0f, 0.0f, 279.5f);
    s.camera.pose.up = glm::vec3(0.0f, 0.0f, 1.0f);
    s.camera.fovDegrees = 50.0f;
    const ImageSet ref = bl::test::renderReference(s, kReferenceSpp);
    const std::vector<double> reference1 = regionMeans(bl::test::layerOf(ref, "indirect1"));
    const std::vector<double> reference2 = regionMeans(bl::test::layerOf(ref, "indirect2"));
    const Runs r = renderSeeds(s, {"strategy=mis", "bounces=2", "fit=visible"}, kFastFrames);
    expectConverged(r.final1, reference1, kNoisyTolerance, "visible fit, floor view, mis", 0.0, kNoisyTolerance);
    expectImageMeanConverged(r.final2, reference2, "visible fit, floor view, two-bounce",
                             kFloorViewTwoBounceTolerance);
}
