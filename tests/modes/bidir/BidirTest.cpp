// Mode bidir's estimators against the reference path tracer on the point-lit Cornell box (the
// fixture, its statistics and tolerances: BidirTestFixture.h).
#include "modes/bidir/BidirTestFixture.h"

using namespace bl::test::bidirmode;

namespace {
// The tests that share the point-lit box's runs (vplRuns, bundleRuns, misRuns: each 12 seeds of
// 128-256 frames). ctest runs them as one process (tests/CMakeLists.txt: BidirEstimators), so
// each configuration renders once; as separate processes misRuns rendered four times.
class BidirEstimators : public Bidir {};
} // namespace

TEST_F(BidirEstimators, VplStrategyConvergesToReferenceIndirect1) {
    expectConverged(vplRuns().final1, reference1, kNoisyTolerance, "vpl", kDimRegion);
}

TEST_F(BidirEstimators, BundleStrategyConvergesToReferenceIndirect1) {
    expectConverged(bundleRuns().final1, reference1, kNoisyTolerance, "bundle", kDimRegion);
}

// VPLs from reflective shadow cubes on the GPU (vpl_source = rsm, 64^2 per face, jittered every
// frame): the VPL strategy's image mean converges to the reference's indirect1 (a wrong density,
// e.g. without the texel's Jacobian J / A, moves it by tens of percent). Region by region the VPL
// strategy alone carries a 1/r^2 tail few seeds cannot bound (8 seeds x 512 frames: every region
// within -5.5%..+2.5% of the reference, one region's seeds' spread 5.8%); RsmVplsConvergeRegionByRegion
// tests the RSM's VPLs region by region under MIS, see papers/tokuyoshi-ogaki-2012.md.
TEST_F(BidirEstimators, RsmVplStrategyImageMeanConvergesToReferenceIndirect1) {
    const Runs& r = runs({"strategy=vpl", "bounces=1", "vpl_source=rsm"}, kComparisonFrames);
    expectImageMeanConverged(r.final1, reference1, "rsm vpl, 128 frames", kImageTolerance);
}

TEST_F(BidirEstimators, MisConvergesToReferenceIndirect1) {
    expectConverged(misRuns().final1, reference1, kTolerance, "mis");
}

// MIS at equal samples (the same seeds, frames and pairs) has less error than either strategy
// alone (Fig. 4's point: VPLs spike near corners, bundles miss small bright regions; MIS neither).
// (The MIS runs' VPL cubes are finer, kMisVplCubes: at 128^2 too MIS had 1.1e-5 against 3.0e-5
// and 3.5e-5.)
TEST_F(BidirEstimators, MisHasLowerErrorThanEitherStrategy) {
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
TEST_F(BidirEstimators, TwoBounceUnclampedConvergesToReferenceIndirect2) {
    expectConverged(misRuns().final2, reference2, kTwoBounceTolerance, "two-bounce", kDimRegion);
}

// Clamping |x1 - x2| to 0.1 of the scene radius is a bias: the energy it loses is the difference
// to the unclamped runs with the same seeds and frames (paired: the same VPLs and bundles, so the
// difference is the clamp's alone, not noise), stated as a share of the reference's indirect2.
// One-bounce light is untouched by it.
TEST_F(BidirEstimators, TwoBounceClampingLosesAStatedShare) {
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
    BL_SKIP_WITHOUT_SCENE_FILES("data/external/cornell-glossy-point.toml");
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
