// The fixture, settings and helpers the bidir mode tests share (BidirTest.cpp: the estimators;
// BidirFeatureTest.cpp: plans, VPL sources, fits, environment, textures). What the tests assert
// and how (statistics, run time):
//
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
#pragma once

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
#include <string>
#include <vector>

namespace bl::test::bidirmode {

using namespace bl;
namespace stats = bl::test::stats;

inline constexpr int kResolution = 32;        // camera pixels per side: the estimator, not the image, is tested
inline constexpr int kRegions = 4;            // R x R regions of 8 x 8 pixels
// Independent runs per configuration (stats::seeds(kSeeds): 1..12). Since the pixel jitter follows
// the seed (core/sampling/PixelSamples.h) the seeds' spread also holds the footprint's integration
// error, which 8 seeds left a few percent above the noise gate in some regions.
inline constexpr std::uint32_t kSeeds = 12;
inline constexpr std::uint32_t kFrames = 256; // frames per run of the single-strategy convergence tests
inline constexpr std::uint32_t kMisFrames = kFrames / 2;
inline constexpr std::uint32_t kFastFrames = 64; // frames per run of the defaults' fast tests (8 seeds: the MIS regions
// at 32 frames spread 1.7-2% of a region, above the noise gate of kTolerance)
// The spot-lit box's corners below the cone get 5-20% of the mean region's indirect light; at 64
// frames their relative spread reaches 7%, so the fast tests hold regions below this share of the
// mean region to the tolerance of that share (expectConverged).
inline constexpr double kDimRegion = 0.25;
// The floor view's two-bounce image mean at 64 frames: its right tail (single paths across the
// walls' corners) spreads the seeds by ~9% (4 seeds: +-4.5%, measured -1.2%); 10% still catches
// a fit that cuts hidden hits (-79%).
inline constexpr double kFloorViewTwoBounceTolerance = 0.10;
inline constexpr std::uint32_t kReferenceSpp = 1024;
inline constexpr const char* kRsm = "rsm_resolution=64"; // texels per RSM cube face side (vpl_source = rsm)
// Environment bundles' test: E bundles per frame, frames per seed (8 seeds: twice the directions
// of the 4 x 24 it had) and the tolerance of its regions and image mean. The sun's few directions
// give the lit regions a heavy tail: their standard error stays at 3.4% of a region at 8 x 24 and
// 8 x 32 frames alike (regions 0 and 7; the image mean's 1.25-1.5%), so the noise gate lets them
// resolve 3 x 3.4%: 12% (measured at 4 x 16: every region within -6.0%..+2.5%). Regions that see mostly sky (direct light below 5% of the mean region's) are left
// out of the region test: their relative error means nothing.
inline constexpr std::uint32_t kEnvironmentBundles = 8;
inline constexpr std::uint32_t kEnvironmentFrames = 24;
inline constexpr double kEnvironmentTolerance = 0.12;
// Frames per seed of the textured-albedo test.
inline constexpr std::uint32_t kTexturedFrames = 32;
inline const std::vector<std::string> kCommon = {"pairs_per_frame=8", "bundle_resolution=128", "shadow_resolution=256",
                                          "vpl_shadow_resolution=128", kRsm};

// Tolerance: shadow cubes (4x4 PCF) and bundle pixels move visibility boundaries by up to a texel
// or pixel, a few percent of a region near contact shadows; the reference's own error at 1024 spp
// over 64 pixels is below 1%.
inline constexpr double kTolerance = 0.05;
// The MIS runs' VPL cubes: at 128^2 the bottom-right floor region (the short block's contact
// shadow) loses 5.5 +- 0.3% under MIS (RSM or traced VPLs alike, 8 seeds x 512 frames), beyond the
// tolerance; at 256^2 (the mode's default) 3% of it comes back (seeds 1-2, 256 frames: 0.91 ->
// 0.94, 0.94 -> 0.97 of the reference; bundles at 256^2 change nothing).
inline constexpr const char* kMisVplCubes = "vpl_shadow_resolution=256";
// The single strategies alone and the unclamped two-bounce term (VPL strategy: the 1/r^2 tail;
// bundle strategy: small bright regions missed) spread their regions' seeds far more than MIS's
// one-bounce term: at 8 seeds x 256 frames (two-bounce: x 128) the standard error reaches 3.5% of
// a region (vpl region 14, bundle 12-13, two-bounce 8-9; MIS at most 1.4%), so the noise gate
// (stderr <= tolerance / 3) lets them resolve 10%, not kTolerance: they are held to 10% region by
// region (dim regions floored at kDimRegion), MIS's one-bounce regions to kTolerance, and every
// image mean to kImageTolerance.
inline constexpr double kNoisyTolerance = 0.10;
// The unclamped two-bounce term's regions under MIS (8 seeds x 128 frames) reach a standard error
// of 3.9% of the region (region 13, bottom row): the gate needs 3 x 3.9%.
inline constexpr double kTwoBounceTolerance = 0.12;
// RsmVplsConvergeRegionByRegion (MIS, bounces 1, 8 seeds x kFastFrames): the point light's region
// 12 spreads 1.74% of the region, the gate needs 3 x 1.74%.
inline constexpr double kRsmMisTolerance = 0.06;
// The image mean averages those boundary shifts out: measured -1% to -2% for all three strategies.
inline constexpr double kImageTolerance = 0.03;
// Frames of the equal-sample error comparison (read from the convergence runs).
inline constexpr std::uint32_t kComparisonFrames = 128;
// two_bounce_clamp of the clamped run (|x1 - x2| >= 0.1 of the scene radius) and the share of
// the reference's indirect2 it loses on this scene: measured 1.76 +- 0.06% (seeds 1.63-1.88%,
// 128 frames); the test brackets it by [1%, 3%].
inline constexpr const char* kClamp = "two_bounce_clamp=0.1";
inline constexpr std::uint32_t kClampFrames = kComparisonFrames; // paired with the unclamped runs' frame 128
inline constexpr double kClampLossMin = 0.01;
inline constexpr double kClampLossMax = 0.03;
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
inline constexpr std::uint32_t kGlossyFrames = 64;
inline constexpr double kGlossyTolerance = kNoisyTolerance;

inline Scene cornellPoint() {
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell-point.toml"));
    s.camera.resolution = {kResolution, kResolution};
    return s;
}

inline double counterOf(const ImageSet& out, const std::string& name) {
    for (const auto& [key, value] : out.counters) {
        if (key == name) return value;
    }
    ADD_FAILURE() << "no counter " << name;
    return -1.0;
}

// Mean of each channel over an image.
inline glm::dvec3 channelMeans(const Image& image) {
    glm::dvec3 sum(0.0);
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) sum += glm::dvec3(image.at(x, y));
    return sum / double(image.width() * image.height());
}

using stats::luminance;

// Mean luminance of each of the kRegions x kRegions regions of an image.
inline std::vector<double> regionMeans(const Image& image) { return stats::blockMeans(image, kResolution / kRegions); }

inline double imageMean(const std::vector<double>& regions) {
    double sum = 0.0;
    for (double v : regions) sum += v / double(regions.size());
    return sum;
}

// Per seed, the image mean (the regions are equal in area): its spread over seeds is the image's
// own, the regions of one run being correlated (one VPL lights them all).
inline std::vector<double> imageMeans(const std::vector<std::vector<double>>& perSeed) {
    std::vector<double> means;
    for (const auto& regions : perSeed) means.push_back(imageMean(regions));
    return means;
}

// Per seed, the squared error against the reference summed over the regions.
inline std::vector<double> squaredErrors(const std::vector<std::vector<double>>& perSeed, const std::vector<double>& reference) {
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
inline void expectImageMeanConverged(const std::vector<std::vector<double>>& perSeed, const std::vector<double>& reference,
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
inline void expectConverged(const std::vector<std::vector<double>>& perSeed, const std::vector<double>& reference,
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

    inline static std::vector<double> reference1, reference2;
    inline static std::map<std::string, Runs> cache;
};

} // namespace bl::test::bidirmode
