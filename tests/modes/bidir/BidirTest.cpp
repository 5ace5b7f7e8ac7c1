// Mode bidir's one-bounce estimator ([TO12] Eq. 3-6): each strategy alone converges to the
// reference path tracer's `indirect1` layer on the Cornell box lit by a point light, and MIS has
// lower error than either at equal samples.
//
// Statistics: S independent seeds per strategy, each F frames of K pairs. For each of R x R image
// regions, the seeds' region means give a mean and a standard error (the seeds' spread); the test
// asserts |mean - reference| within the stated tolerance and that the spread is small enough for
// that tolerance to mean something (else the test could not fail).
#include "modes/Registry.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <cmath>
#include <cstdio>

using namespace bl;

namespace {

constexpr int kResolution = 32;        // camera pixels per side: the estimator, not the image, is tested
constexpr int kRegions = 4;            // R x R regions of 8 x 8 pixels
constexpr std::uint32_t kSeeds = 4;    // independent runs per strategy
constexpr std::uint32_t kFrames = 512; // frames per run of the convergence tests
constexpr std::uint32_t kReferenceSpp = 1024;
const std::vector<std::string> kCommon = {"pairs_per_frame=8", "bundle_resolution=128", "shadow_resolution=256",
                                          "vpl_shadow_resolution=128"};

// Tolerance: shadow cubes (4x4 PCF) and bundle pixels move visibility boundaries by up to a texel
// or pixel, a few percent of a region near contact shadows; the reference's own error at 1024 spp
// over 64 pixels is below 1%.
constexpr double kTolerance = 0.05;
// The image mean averages those boundary shifts out: measured -1% to -2% for all three strategies.
constexpr double kImageTolerance = 0.03;
// Frames per strategy of the equal-sample error comparison.
constexpr std::uint32_t kComparisonFrames = 128;

Scene cornellPoint() {
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell-point.toml"));
    s.camera.resolution = {kResolution, kResolution};
    return s;
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
};

class Bidir : public bl::test::VulkanTest {
protected:
    static void SetUpTestSuite() {
        Scene s = cornellPoint();
        reference = regionMeans(bl::test::layerOf(bl::test::renderReference(s, kReferenceSpp), "indirect1"));
    }

    RegionStats run(const std::string& strategy, std::uint32_t frames = kFrames) {
        Scene s = cornellPoint();
        std::vector<std::vector<double>> perSeed;
        for (std::uint32_t seed = 0; seed < kSeeds; ++seed) {
            std::vector<std::string> settings = kCommon;
            settings.push_back("strategy=" + strategy);
            std::unique_ptr<Mode> mode = createMode("bidir", settings);
            mode->setScene(s, &ctx());
            for (std::uint32_t f = 0; f < frames; ++f) mode->iterate({f, seed + 1, 0.0});
            ImageSet out = mode->resolve();
            EXPECT_EQ(out.nonFiniteSamples, 0u);
            perSeed.push_back(regionMeans(bl::test::layerOf(out, "indirect1")));
        }
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
        return r;
    }

    // Every region within `tolerance` (relative) of the reference, plus three standard errors of
    // the seeds' mean; and that standard error itself below `tolerance`, so the bound is tight.
    void expectConverged(const RegionStats& r, double tolerance, const char* name) {
        for (int i = 0; i < kRegions * kRegions; ++i) {
            const double ref = reference[i];
            std::printf("%s region %2d: %.5f +- %.5f  reference %.5f  (%+.1f%%)\n", name, i, r.mean[i], r.stderr_[i],
                        ref, 100.0 * (r.mean[i] / ref - 1.0));
            EXPECT_LT(r.stderr_[i], tolerance * ref) << name << " region " << i << ": too noisy to test";
            EXPECT_NEAR(r.mean[i], ref, tolerance * ref + 3.0 * r.stderr_[i]) << name << " region " << i;
        }
        // The image mean (all regions are equal in area): what a user compares first.
        double mean = 0.0, ref = 0.0, variance = 0.0;
        for (int i = 0; i < kRegions * kRegions; ++i) {
            mean += r.mean[i];
            ref += reference[i];
            variance += r.stderr_[i] * r.stderr_[i]; // regions of one run are correlated: an estimate
        }
        std::printf("%s: image mean %.5f reference %.5f (%+.2f%%), summed squared region error %.3g\n", name, mean, ref,
                    100.0 * (mean / ref - 1.0), r.squaredError);
        EXPECT_NEAR(mean, ref, kImageTolerance * ref + 3.0 * std::sqrt(variance)) << name << " image mean";
    }

    static std::vector<double> reference;
};
std::vector<double> Bidir::reference;


} // namespace

TEST_F(Bidir, VplStrategyConvergesToReferenceIndirect1) { expectConverged(run("vpl"), kTolerance, "vpl"); }

TEST_F(Bidir, BundleStrategyConvergesToReferenceIndirect1) { expectConverged(run("bundle"), kTolerance, "bundle"); }

TEST_F(Bidir, MisConvergesToReferenceIndirect1) { expectConverged(run("mis", kFrames / 2), kTolerance, "mis"); }

// MIS at equal samples (the same seeds, frames and pairs) has less error than either strategy
// alone (Fig. 4's point: VPLs spike near corners, bundles miss small bright regions; MIS neither).
TEST_F(Bidir, MisHasLowerErrorThanEitherStrategy) {
    const double mis = run("mis", kComparisonFrames).squaredError;
    const double vpl = run("vpl", kComparisonFrames).squaredError;
    const double bundle = run("bundle", kComparisonFrames).squaredError;
    std::printf("summed squared region error at %u frames: mis %.3g, vpl %.3g, bundle %.3g\n", kComparisonFrames, mis,
                vpl, bundle);
    EXPECT_LT(mis, vpl);
    EXPECT_LT(mis, bundle);
}
