// Mode bidir's estimators against the reference path tracer on the Cornell box lit by a point
// light: the one-bounce term ([TO12] Eq. 3-6) by each strategy alone converges to the reference's
// `indirect1` layer and MIS has lower error than either at equal samples; the two-bounce term
// (Eq. 7-8) converges to `indirect2` unclamped and loses a stated share of it clamped. The MIS
// runs use the mode's defaults (VPLs from reflective shadow maps, bundle frames fitted to the
// visible points); the VPL strategy's runs trace their VPLs (vpl_source = traced, the exact
// sampler the RSM is checked against), whose 1/r^2 tail four seeds bound.
//
// Statistics: S independent seeds per configuration, each F frames of K pairs. For each of R x R
// image regions, the seeds' region means give a mean and a standard error (the seeds' spread); the
// test asserts |mean - reference| within the stated tolerance and that the spread is small enough
// for that tolerance to mean something (else the test could not fail).
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
#include "support/TestFiles.h"
#include "support/TexturedScenes.h"
#include "support/VulkanTest.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <shared/Lights.h>

using namespace bl;

namespace {

constexpr int kResolution = 32;        // camera pixels per side: the estimator, not the image, is tested
constexpr int kRegions = 4;            // R x R regions of 8 x 8 pixels
constexpr std::uint32_t kSeeds = 4;    // independent runs per configuration
constexpr std::uint32_t kFrames = 512; // frames per run of the single-strategy convergence tests
constexpr std::uint32_t kMisFrames = kFrames / 2;
constexpr std::uint32_t kFastFrames = 64; // frames per run of the defaults' fast tests
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
// Environment bundles' test: E bundles per frame, frames per seed, and the region tolerance (the
// seeds' spread at 192 directions is 2-6% of a region; measured at 128 directions: every region
// within -6.0%..+2.5%, the image mean -0.34 +- 1.21%). Regions that see mostly sky (direct light
// below 5% of the mean region's) are left out: their relative error means nothing.
constexpr std::uint32_t kEnvironmentBundles = 8;
constexpr std::uint32_t kEnvironmentFrames = 24;
constexpr double kEnvironmentTolerance = 0.10;
// Frames per seed of the textured-albedo test.
constexpr std::uint32_t kTexturedFrames = 64;
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
// faces) and the region tolerance of indirect1 (checked with the seeds' spread as above): the
// ceiling's regions, the dimmest (1% of the image's indirect light each) and lit only from below
// at grazing angles, measured -9.3 +- 1.2% (top right) and +7.0 +- 2.9% (top left) at 64 frames
// (-8.1% / +6.4% at 128: not noise, the 128^2 cubes' and bundles' resolution there, not separated
// yet); every other region within 6%, the image mean -0.5 +- 0.7%.
constexpr std::uint32_t kGlossyFrames = 64;
constexpr double kGlossyTolerance = 0.10;

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

double luminance(const glm::vec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// Mean luminance of each region of an image.
std::vector<double> regionMeans(const Image& image) {
    std::vector<double> means(kRegions * kRegions, 0.0);
    const int side = kResolution / kRegions;
    for (int y = 0; y < kResolution; ++y) {
        for (int x = 0; x < kResolution; ++x) {
            means[(y / side) * kRegions + x / side] += luminance(image.at(x, y)) / double(side * side);
        }
    }
    return means;
}

struct RegionStats {
    std::vector<double> mean;   // over seeds
    std::vector<double> stderr_; // of that mean, from the seeds' spread
    double squaredError = 0.0;  // per-seed squared error against the reference, summed over regions, mean over seeds
    double imageStderr = 0.0;   // of the image mean (the regions' sum), from the seeds' image means: the
                                // regions of one run are correlated (one VPL lights them all)
};

RegionStats statsOf(const std::vector<std::vector<double>>& perSeed, const std::vector<double>& reference) {
    RegionStats r;
    for (int i = 0; i < kRegions * kRegions; ++i) {
        double sum = 0.0, sum2 = 0.0;
        for (const auto& m : perSeed) {
            sum += m[i];
            sum2 += m[i] * m[i];
            r.squaredError += (m[i] - reference[i]) * (m[i] - reference[i]) / kSeeds;
        }
        const double mean = sum / kSeeds;
        const double variance = std::max(0.0, (sum2 - kSeeds * mean * mean) / (kSeeds - 1));
        r.mean.push_back(mean);
        r.stderr_.push_back(std::sqrt(variance / kSeeds));
    }
    double sum = 0.0, sum2 = 0.0;
    for (const auto& m : perSeed) {
        double image = 0.0;
        for (double v : m) image += v;
        sum += image;
        sum2 += image * image;
    }
    const double mean = sum / kSeeds;
    r.imageStderr = std::sqrt(std::max(0.0, (sum2 - kSeeds * mean * mean) / (kSeeds - 1)) / kSeeds);
    return r;
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
        for (std::uint32_t seed = 0; seed < kSeeds; ++seed) {
            std::vector<std::string> settings = kCommon;
            settings.insert(settings.end(), extra.begin(), extra.end());
            std::unique_ptr<Mode> mode = createMode("bidir", settings);
            mode->setScene(s, &ctx());
            for (std::uint32_t f = 0; f < frames; ++f) {
                mode->iterate({f, seed + 1, 0.0});
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

    // Every region within `tolerance` (relative) of the reference, plus three standard errors of
    // the seeds' mean; and that standard error itself below `tolerance`, so the bound is tight.
    // Regions dimmer than `floor` times the mean region are held to `tolerance` of that floor
    // instead of their own value (a region with 5% of the mean's light matters as much to the
    // image at 5% error as the mean region at 0.25%).
    static void expectConverged(const RegionStats& r, const std::vector<double>& reference, double tolerance,
                                const char* name, double floor = 0.0) {
        double meanRegion = 0.0;
        for (double v : reference) meanRegion += v / double(reference.size());
        for (int i = 0; i < kRegions * kRegions; ++i) {
            const double ref = std::max(reference[i], floor * meanRegion);
            std::printf("%s region %2d: %.5f +- %.5f  reference %.5f  (%+.1f%%)\n", name, i, r.mean[i], r.stderr_[i],
                        reference[i], 100.0 * (r.mean[i] / reference[i] - 1.0));
            EXPECT_LT(r.stderr_[i], tolerance * ref) << name << " region " << i << ": too noisy to test";
            EXPECT_NEAR(r.mean[i], reference[i], tolerance * ref + 3.0 * r.stderr_[i]) << name << " region " << i;
        }
        // The image mean (all regions are equal in area): what a user compares first.
        double mean = 0.0, ref = 0.0;
        for (int i = 0; i < kRegions * kRegions; ++i) {
            mean += r.mean[i];
            ref += reference[i];
        }
        std::printf("%s: image mean %.5f reference %.5f (%+.2f%%) +- %.2f%%, summed squared region error %.3g\n", name,
                    mean, ref, 100.0 * (mean / ref - 1.0), 100.0 * r.imageStderr / ref, r.squaredError);
        EXPECT_NEAR(mean, ref, kImageTolerance * ref + 3.0 * r.imageStderr) << name << " image mean";
    }

    static std::vector<double> reference1, reference2;
    static std::map<std::string, Runs> cache;
};
std::vector<double> Bidir::reference1, Bidir::reference2;
std::map<std::string, Runs> Bidir::cache;

double imageMean(const std::vector<double>& regions) {
    double sum = 0.0;
    for (double v : regions) sum += v;
    return sum;
}

// The image mean alone (for layers whose regions a few seeds cannot bound) within `tolerance`
// plus three standard errors of the seeds' mean, that error itself below `tolerance`.
void expectImageMeanConverged(const RegionStats& r, const std::vector<double>& reference, const char* name,
                              double tolerance = kImageTolerance) {
    const double mean = imageMean(r.mean), ref = imageMean(reference);
    std::printf("%s: image mean %.5f reference %.5f (%+.2f%%) +- %.2f%%\n", name, mean, ref, 100.0 * (mean / ref - 1.0),
                100.0 * r.imageStderr / ref);
    EXPECT_LT(r.imageStderr, tolerance * ref) << name << ": too noisy to test";
    EXPECT_NEAR(mean, ref, tolerance * ref + 3.0 * r.imageStderr) << name;
}

} // namespace

TEST_F(Bidir, VplStrategyConvergesToReferenceIndirect1) {
    expectConverged(statsOf(vplRuns().final1, reference1), reference1, kTolerance, "vpl");
}

TEST_F(Bidir, BundleStrategyConvergesToReferenceIndirect1) {
    expectConverged(statsOf(bundleRuns().final1, reference1), reference1, kTolerance, "bundle");
}

// VPLs from reflective shadow cubes on the GPU (vpl_source = rsm, 64^2 per face, jittered every
// frame): the VPL strategy's image mean converges to the reference's indirect1 (a wrong density,
// e.g. without the texel's Jacobian J / A, moves it by tens of percent). Region by region the VPL
// strategy alone carries a 1/r^2 tail four seeds cannot bound (8 seeds x 512 frames: every region
// within -5.5%..+2.5% of the reference, one region's seeds' spread 5.8%); RsmVplsConvergeRegionByRegion
// tests the RSM's VPLs region by region under MIS, see papers/tokuyoshi-ogaki-2012.md.
TEST_F(Bidir, RsmVplStrategyImageMeanConvergesToReferenceIndirect1) {
    const Runs& r = runs({"strategy=vpl", "bounces=1", "vpl_source=rsm"}, kComparisonFrames);
    expectImageMeanConverged(statsOf(r.final1, reference1), reference1, "rsm vpl, 128 frames");
}

TEST_F(Bidir, MisConvergesToReferenceIndirect1) {
    expectConverged(statsOf(misRuns().final1, reference1), reference1, kTolerance, "mis");
}

// MIS at equal samples (the same seeds, frames and pairs) has less error than either strategy
// alone (Fig. 4's point: VPLs spike near corners, bundles miss small bright regions; MIS neither).
// (The MIS runs' VPL cubes are finer, kMisVplCubes: at 128^2 too MIS had 1.1e-5 against 3.0e-5
// and 3.5e-5.)
TEST_F(Bidir, MisHasLowerErrorThanEitherStrategy) {
    const double mis = statsOf(misRuns().early1, reference1).squaredError;
    const double vpl = statsOf(vplRuns().early1, reference1).squaredError;
    const double bundle = statsOf(bundleRuns().early1, reference1).squaredError;
    std::printf("summed squared region error at %u frames: mis %.3g, vpl %.3g, bundle %.3g\n", kComparisonFrames, mis,
                vpl, bundle);
    EXPECT_LT(mis, vpl);
    EXPECT_LT(mis, bundle);
}

// The unclamped two-bounce term (one VPL, one bundle hit, the VPL's shadow cube between them)
// converges to the reference's indirect2 layer, with the one-bounce tolerance.
TEST_F(Bidir, TwoBounceUnclampedConvergesToReferenceIndirect2) {
    expectConverged(statsOf(misRuns().final2, reference2), reference2, kTolerance, "two-bounce");
}

// Clamping |x1 - x2| to 0.1 of the scene radius is a bias: the energy it loses is the difference
// to the unclamped runs with the same seeds and frames (paired: the same VPLs and bundles, so the
// difference is the clamp's alone, not noise), stated as a share of the reference's indirect2.
// One-bounce light is untouched by it.
TEST_F(Bidir, TwoBounceClampingLosesAStatedShare) {
    const Runs& clamped = runs({"strategy=mis", "bounces=2", kMisVplCubes, kClamp}, kClampFrames);
    const Runs& unclamped = misRuns();
    const double ref = imageMean(reference2);
    double sum = 0.0, sum2 = 0.0, biasSum = 0.0;
    for (std::uint32_t s = 0; s < kSeeds; ++s) {
        const double loss = (imageMean(unclamped.early2[s]) - imageMean(clamped.final2[s])) / ref;
        std::printf("seed %u: clamping loses %.2f%% of indirect2\n", s + 1, 100.0 * loss);
        sum += loss;
        sum2 += loss * loss;
        biasSum += imageMean(clamped.final2[s]) / ref - 1.0;
        EXPECT_EQ(clamped.final1[s], unclamped.early1[s]) << "seed " << s << ": one-bounce changed";
    }
    const double loss = sum / kSeeds;
    const double spread = std::sqrt(std::max(0.0, (sum2 - kSeeds * loss * loss) / (kSeeds - 1)) / kSeeds);
    std::printf("two-bounce clamped (%s): loses %.2f%% +- %.2f%% of the reference's indirect2; clamped image mean "
                "%+.2f%% against it (%u frames)\n",
                kClamp, 100.0 * loss, 100.0 * spread, 100.0 * biasSum / kSeeds, kClampFrames);
    EXPECT_GT(loss, kClampLossMin);
    EXPECT_LT(loss, kClampLossMax);
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
    for (std::uint32_t seed = 0; seed < kSeeds; ++seed) {
        std::vector<std::string> settings = kCommon;
        settings.insert(settings.end(), {"strategy=mis", "bounces=2", "suppression=none"});
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < kGlossyFrames; ++f) mode->iterate({f, seed + 1, 0.0});
        ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        perSeed1.push_back(regionMeans(bl::test::layerOf(out, "indirect1")));
        perSeed2.push_back(regionMeans(bl::test::layerOf(out, "indirect2")));
    }
    expectConverged(statsOf(perSeed1, glossy1), glossy1, kGlossyTolerance, "glossy one-bounce");
    expectImageMeanConverged(statsOf(perSeed2, glossy2), glossy2, "glossy two-bounce");
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
    for (std::uint32_t seed = 0; seed < kSeeds; ++seed) {
        std::vector<std::string> settings = kCommon;
        settings.push_back("environment_bundles=" + std::to_string(kEnvironmentBundles));
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        for (const PlannedPass& p : mode->plan(s)) {
            if (p.name == "environment bundles") {
                EXPECT_TRUE(p.runs) << p.reason;
            }
        }
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < kEnvironmentFrames; ++f) mode->iterate({f, seed + 1, 0.0});
        ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        EXPECT_EQ(counterOf(out, "dropped_samples"), 0.0);
        perSeed.push_back(regionMeans(bl::test::layerOf(out, "direct")));
    }
    const RegionStats stats = statsOf(perSeed, reference);
    double meanRegion = 0.0;
    for (double r : reference) meanRegion += r / reference.size();
    double mean = 0.0, ref = 0.0, variance = 0.0;
    for (int i = 0; i < kRegions * kRegions; ++i) {
        mean += stats.mean[i];
        ref += reference[i];
        variance += stats.stderr_[i] * stats.stderr_[i];
        std::printf("environment direct region %2d: %.5f +- %.5f  reference %.5f\n", i, stats.mean[i], stats.stderr_[i],
                    reference[i]);
        if (reference[i] < 0.05 * meanRegion) continue;
        EXPECT_LT(stats.stderr_[i], kEnvironmentTolerance * reference[i]) << "region " << i << ": too noisy to test";
        EXPECT_NEAR(stats.mean[i], reference[i], kEnvironmentTolerance * reference[i] + 3.0 * stats.stderr_[i])
            << "region " << i;
    }
    std::printf("environment direct: image mean %.5f reference %.5f (%+.2f%%) +- %.2f%%\n", mean, ref,
                100.0 * (mean / ref - 1.0), 100.0 * std::sqrt(variance) / ref);
    EXPECT_NEAR(mean, ref, kImageTolerance * ref + 3.0 * std::sqrt(variance));

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
// indirect1's blue channel far off (+17% for multibounce's same scene). Each channel's image mean
// of indirect1 against the reference's, with the seeds' spread.
TEST_F(Bidir, TexturedAlbedoAtBundleHitsAndRsmVpls) {
    Scene s = cornellPoint();
    ASSERT_TRUE(bl::test::texturePlanar(s, "floor", bl::test::redGreenTexture()));
    const ImageSet ref = bl::test::renderReference(s, kReferenceSpp);
    const glm::dvec3 reference = channelMeans(bl::test::layerOf(ref, "indirect1"));
    for (const std::vector<std::string>& extra :
         {std::vector<std::string>{"strategy=bundle", "bounces=1"},
          std::vector<std::string>{"strategy=vpl", "bounces=1", "vpl_source=rsm"}}) {
        glm::dvec3 sum(0.0), sum2(0.0);
        for (std::uint32_t seed = 0; seed < kSeeds; ++seed) {
            std::vector<std::string> settings = kCommon;
            settings.insert(settings.end(), extra.begin(), extra.end());
            std::unique_ptr<Mode> mode = createMode("bidir", settings);
            mode->setScene(s, &ctx());
            for (std::uint32_t f = 0; f < kTexturedFrames; ++f) mode->iterate({f, seed + 1, 0.0});
            const glm::dvec3 m = channelMeans(bl::test::layerOf(mode->resolve(), "indirect1"));
            sum += m;
            sum2 += m * m;
        }
        const glm::dvec3 mean = sum / double(kSeeds);
        const glm::dvec3 spread = glm::sqrt(glm::max(glm::dvec3(0.0), (sum2 - double(kSeeds) * mean * mean) /
                                                                         double(kSeeds - 1) / double(kSeeds)));
        for (int c = 0; c < 3; ++c) {
            std::printf("%s: indirect1 channel %d %.5f +- %.5f reference %.5f (%+.2f%%)\n", extra[0].c_str(), c, mean[c],
                        spread[c], reference[c], 100.0 * (mean[c] / reference[c] - 1.0));
            EXPECT_NEAR(mean[c], reference[c], kImageTolerance * reference[c] + 3.0 * spread[c]) << extra[0] << " " << c;
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
// wrong VPL position, normal, albedo, intensity or density shows in its region. 4 seeds x 64
// frames per light, a few seconds each.
TEST_F(Bidir, RsmVplsConvergeRegionByRegion) {
    for (const bool spot : {false, true}) {
        const Scene s = spot ? cornellSpot() : cornellPoint();
        const std::vector<double> reference = regionMeans(bl::test::layerOf(bl::test::renderReference(s, kReferenceSpp), "indirect1"));
        const Runs r = renderSeeds(s, {"strategy=mis", "bounces=1", "vpl_source=rsm", kMisVplCubes}, kFastFrames);
        expectConverged(statsOf(r.final1, reference), reference, kTolerance, spot ? "rsm mis, spot" : "rsm mis, point",
                        kDimRegion);
    }
}

// Bundle frames fitted to the visible points (fit = visible, the default) must still find every
// surface along a visible point's ray, not only visible ones: the camera looks straight down at the
// floor and the blocks' tops, so a bundle's next vertex y is almost always a wall, the ceiling or
// a block's side, none of them seen. MIS with the two-bounce term (whose second vertex is that
// hit): indirect1 converges to the reference region by region, indirect2 in the image mean (its
// regions carry the unclamped term's 1/r^2 tail). 4 seeds x 64 frames. Mutation: the bundles'
// depth range fitted to the visible points too (indirect1 -24.8%, indirect2 -78.6%).
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
    expectConverged(statsOf(r.final1, reference1), reference1, kTolerance, "visible fit, floor view, mis");
    expectImageMeanConverged(statsOf(r.final2, reference2), reference2, "visible fit, floor view, two-bounce",
                             kFloorViewTwoBounceTolerance);
}
