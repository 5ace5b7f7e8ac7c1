// Mode atlas in the furnace: a closed box of albedo 1/2 emitting 1 inward, every radiance 2 less the
// interleaved transfer's missing bounces (exact, AtlasBias.h); texels, image and path-length limits.
#include "modes/atlas/AtlasTestFixture.h"

#include <algorithm>
#include <cmath>

using namespace bl;
using namespace bl::test::atlasmode;

namespace {

// The furnace: the expected radiance is exact (constant radiance: the texel average and the
// bilinear lookup change nothing; exact texel areas) up to the interleaved transfer's missing
// bounces (furnaceExpectation), so a tolerance only gives the noise gate a scale: what the seeds
// resolve, centred on the closed form. Texel means: 0.3% (8 seeds of 128 directions: stderr
// 0.07%); bounce-by-bounce passes of 32 directions: 0.25% (stderr 0.03-0.06%); the camera's image (8 seeds of 64
// directions, 32^2 pixels): 4%.
constexpr double kFurnaceTolerance = 0.003;
constexpr double kFurnacePassTolerance = 0.0025;
constexpr double kFurnaceImageTolerance = 0.04;
// Per texel (or pixel) of the furnace, Holm-corrected over the texels: 2% (per pixel 6%), what the
// seeds resolve; a wrong texel area at a triangle border (the atlas's own shares were off by 10-50%
// there) is far larger.
constexpr double kFurnaceTexelTolerance = 0.02;
constexpr double kFurnacePixelTolerance = 0.06;
// NOT DERIVED: interleaved transfer falls short of furnaceExpectation by a further ~0.9 / n (n
// directions; absolute, on the furnace's 2) that the recursion does not predict. Measured with
// 8 seeds: 0.94 / n at n = 32, 0.96 / n at 128 (with weighting k = 2; k = 0 at 32: 0.60 / n), and
// one seed 0.89 / n at 1024; the same with `directions=random` (so not the shuffled Halton
// blocks' sampling without replacement); bounce-by-bounce transfer (a fixed sender) shows none.
// An O(1/n) deficit is what a correlation between a direction's transport and the sender it reads
// would give; its cause is open (issue 19). The interleaved furnace tests expect it, stated here
// so that a change in it fails them.
constexpr double kInterleavedShortfall = 0.9;
// Radiance of the furnace's inner (front) sides against `expected`: the area-weighted mean, the
// largest deviation of a texel, and the texels counted.
struct FurnaceStats {
    double mean = 0.0, worst = 0.0;
    std::size_t counted = 0;
};
FurnaceStats furnaceStats(const Mode& mode, double expected) {
    const AtlasMode::TexelRadiance texels = static_cast<const AtlasMode&>(mode).readTexels();
    FurnaceStats f;
    double areaSum = 0.0;
    for (std::size_t t = 0; t < texels.area.size(); ++t) {
        if (texels.area[t] <= 0.0f) continue;
        const double l = texels.emission[t].x + texels.reflected[2 * t].x; // the inner side is the front
        f.worst = std::max(f.worst, std::abs(l - expected));
        f.mean += l * texels.area[t];
        areaSum += texels.area[t];
        ++f.counted;
    }
    f.mean /= areaSum;
    return f;
}

// The furnace's expected texel radiance after n directions of interleaved transfer: emission 1
// plus the reflections' shares (AtlasBias.h), 1 + sum_b c(n, b) / 2^b.
double furnaceExpectation(std::uint32_t directions) {
    const std::vector<double> c = bias::interleavedShares(directions, kWeighting, 64);
    double e = 1.0;
    for (std::size_t b = 1; b < c.size(); ++b) e += c[b] * std::pow(0.5, double(b));
    return e;
}

// What the interleaved furnace tests expect: the closed form less the shortfall the derivation
// does not explain (kInterleavedShortfall: measured, stated).
double furnaceInterleaved(std::uint32_t directions) {
    const double e = furnaceExpectation(directions), shortfall = kInterleavedShortfall / double(directions);
    std::printf("furnace after %u interleaved directions: %.5f derived, %.5f less the unexplained shortfall %.5f\n",
                directions, e, e - shortfall, shortfall);
    return e - shortfall;
}

// The furnace's inner-side radiance of every texel with area (index order fixed by the atlas).
std::vector<double> furnaceTexels(const Mode& mode) {
    const AtlasMode::TexelRadiance texels = static_cast<const AtlasMode&>(mode).readTexels();
    std::vector<double> out;
    for (std::size_t t = 0; t < texels.area.size(); ++t) {
        if (texels.area[t] > 0.0f) out.push_back(texels.emission[t].x + texels.reflected[2 * t].x);
    }
    return out;
}

// Every element (texel, pixel) of perSeed[s][e] within `tolerance` of `expected`, behind the noise
// gate, Holm-corrected over the elements (one line: the worst element and the count rejected).
::testing::AssertionResult elementsAgree(const std::vector<std::vector<double>>& perSeed, double expected,
                                         double tolerance, const std::string& what) {
    const std::size_t count = perSeed.front().size();
    std::vector<double> pValues;
    std::size_t noisy = 0, worst = 0;
    double worstDeviation = 0.0, worstStderr = 0.0, largestStderr = 0.0;
    for (std::size_t e = 0; e < count; ++e) {
        std::vector<double> values;
        for (const auto& seed : perSeed) values.push_back(seed.at(e));
        const stats::Summary s = stats::summarize(values);
        pValues.push_back(stats::pValue(s, expected, tolerance));
        if (!stats::quietEnough(s, tolerance, what)) ++noisy;
        largestStderr = std::max(largestStderr, s.stderr_);
        if (std::abs(s.mean - expected) > worstDeviation) {
            worstDeviation = std::abs(s.mean - expected);
            worst = e;
            worstStderr = s.stderr_;
        }
    }
    const std::vector<bool> rejected = stats::holmRejects(pValues, stats::kAlpha);
    const std::size_t off = std::size_t(std::count(rejected.begin(), rejected.end(), true));
    std::printf("%s: %zu elements, worst %zu off by %.4g (stderr %.3g), largest stderr %.3g, tolerance %.3g: %zu "
                "rejected, %zu too noisy\n",
                what.c_str(), count, worst, worstDeviation, worstStderr, largestStderr, tolerance, off, noisy);
    if (off == 0 && noisy == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << what << ": " << off << " of " << count
                                         << " rejected by Holm's procedure (worst element " << worst << " off by "
                                         << worstDeviation << ", stderr " << worstStderr << "), " << noisy
                                         << " with stderr above a third of the tolerance " << tolerance;
}

} // namespace

// A closed box of albedo 1/2 emitting radiance 1 inward everywhere: the radiance of every texel's
// inner side is 1 / (1 - 1/2) = 2, less the interleaved transfer's missing bounces after n
// directions (exact: furnaceExpectation, 1.99876 at 128; less kInterleavedShortfall). Checks the estimator's weight
// rho a_pix / (pi p_r A_T), the exact texel areas (the atlas's own shares are off by 10-50% at
// triangle borders) and the interleaved sender: the area-weighted mean within kFurnaceTolerance,
// every texel within kFurnaceTexelTolerance (Holm over the texels). 8 seeds: 1.99127 +- 0.00146
// (stderr). Mutation: the exchange's received light x 1.10 gives 2.2066 (fails).
TEST_F(Atlas, FurnaceTexelsReachTwo) {
    Scene s = loadSmall("data/analytic/furnace.toml", 16);
    constexpr std::uint32_t kDirections = 128;
    const double expected = furnaceInterleaved(kDirections);
    std::vector<double> means;
    std::vector<std::vector<double>> texels;
    for (std::uint32_t seed : stats::seeds(kSeeds)) {
        std::unique_ptr<Mode> mode = run(s, kDirections, {"atlas_resolution=64", "bundle_resolution=256"}, seed);
        means.push_back(furnaceStats(*mode, expected).mean);
        texels.push_back(furnaceTexels(*mode));
    }
    EXPECT_GT(texels.front().size(), 100u);
    expectSeedsAgree(means, expected, kFurnaceTolerance * expected, "furnace texels, area-weighted mean");
    EXPECT_TRUE(elementsAgree(texels, expected, kFurnaceTexelTolerance * expected, "furnace texel"));
}

// Delayed indirect light ([HHGM10] section 6.4, delay_indirect = N): the first N directions send
// the emitters' light only, and the one-bounce and multi-bounce estimates are summed apart (each
// weighted j^k over its own directions), so the furnace still reaches 2 texel by texel once the
// multi-bounce channel has run: 1 (emission) + 1/2 (one bounce, a plain mean) + 1/2 (the rest of
// the series, j^k from its first direction).
// 64 of 384 directions direct only (48^2 atlas, 192^2 bundles): mean 1.998, worst texel 0.015 off.
// Mutations: the multi-bounce channel normalized by the one-bounce weights of its directions
// (j counted from direction 1) gives 1.689; emitters sent into the multi-bounce channel too, 2.993.
TEST_F(Atlas, FurnaceDelayedIndirectReachesTwo) {
    Scene s = loadSmall("data/analytic/furnace.toml", 16);
    std::unique_ptr<Mode> mode =
        run(s, 384, {"atlas_resolution=48", "bundle_resolution=192", "delay_indirect=64"});
    const FurnaceStats f = furnaceStats(*mode, 2.0);
    std::printf("furnace delay_indirect=64: area-weighted mean %.5f, worst |L - 2| %.5f\n", f.mean, f.worst);
    EXPECT_NEAR(f.mean, 2.0, 0.01);
    EXPECT_LT(f.worst, 0.05);
}

// The furnace seen by the camera: the view raster, the G-buffer's emission and the shade pass's
// texel lookup (bilinear inside charts: exact on constant radiance) give furnaceInterleaved(64)
// in every pixel (Holm over the pixels) and as the image mean. 8 seeds: 1.9841 +- 0.0077; the
// exchange's received light x 1.10: 2.194 (fails).
TEST_F(Atlas, FurnaceImageIsTwo) {
    Scene s = loadSmall("data/analytic/furnace.toml", kStatResolution);
    constexpr std::uint32_t kDirections = 64;
    const double expected = furnaceInterleaved(kDirections);
    std::vector<double> means;
    std::vector<std::vector<double>> pixels;
    for (std::uint32_t seed : stats::seeds(kSeeds)) {
        ImageSet out =
            run(s, kDirections, {"atlas_resolution=64", "bundle_resolution=256", "view_samples=4"}, seed)->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        std::vector<double> red;
        for (const glm::vec3& p : out.radiance().pixels()) red.push_back(p.x);
        double mean = 0.0;
        for (double v : red) mean += v / double(red.size());
        means.push_back(mean);
        pixels.push_back(std::move(red));
    }
    expectSeedsAgree(means, expected, kFurnaceImageTolerance * expected, "furnace image mean");
    EXPECT_TRUE(elementsAgree(pixels, expected, kFurnacePixelTolerance * expected, "furnace pixel"));
}

// Bounce-by-bounce transfer with path length limits in the furnace (emission 1, albedo 1/2): at most
// 1, 2, 3 segments give 1, 1.5, 1.75 in every texel (the geometric series cut after 0, 1, 2
// reflections), each pass's sender being exactly the previous pass's light: no interleaved
// deficit, so the expectation is exact. kSeeds seeds of 32-direction passes; the mean within
// kFurnacePassTolerance, every texel within kFurnaceTexelTolerance (Holm). 8 seeds: 1.49866 +-
// 0.0005, 1.74838 +- 0.0010 (passes of 64: 1.49985, 1.74992); the exchange's received light x
// 1.10: 1.5485 and 1.8507 (fail).
TEST_F(Atlas, FurnacePathLengthLimits) {
    Scene s = loadSmall("data/analytic/furnace.toml", 16);
    const double expected[] = {1.0, 1.5, 1.75};
    constexpr std::uint32_t kPass = 32;
    for (int segments = 1; segments <= 3; ++segments) {
        const std::uint32_t directions = segments == 1 ? 1u : kPass * std::uint32_t(segments - 1);
        const double e = expected[segments - 1];
        std::vector<double> means;
        std::vector<std::vector<double>> texels;
        // One emitters-only direction is deterministic: two seeds show it.
        for (std::uint32_t seed : stats::seeds(segments == 1 ? 2 : kSeeds)) {
            std::unique_ptr<Mode> mode =
                run(s, directions,
                    {"atlas_resolution=48", "bundle_resolution=192", "transfer=bounce",
                     "bounce_directions=" + std::to_string(kPass), "max_segments=" + std::to_string(segments)},
                    seed);
            means.push_back(furnaceStats(*mode, e).mean);
            texels.push_back(furnaceTexels(*mode));
        }
        const std::string what = "furnace max_segments=" + std::to_string(segments);
        if (segments == 1) {
            for (double m : means) EXPECT_NEAR(m, 1.0, 1e-6) << what;
            continue;
        }
        expectSeedsAgree(means, e, kFurnacePassTolerance * e, what + ", mean");
        EXPECT_TRUE(elementsAgree(texels, e, kFurnaceTexelTolerance * e, what + ", texel"));
    }
}
