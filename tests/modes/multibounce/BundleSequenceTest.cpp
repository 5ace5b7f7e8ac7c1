// Mode multibounce draws the bundle of each segment without replacement along a path (issue 19,
// B2; shaders/modes/multibounce/MultibounceShared.h, the functions the path shader runs). Drawn with
// replacement (k = floor(u K)), a path went back along the bundle it arrived by with probability
// 1 / K: to its previous vertex again, a point mass the weight f cos / p_r treats as if it had the
// continuous density 1 / (2 pi). With independent random directions (the window is used for them,
// and for any sequence when K <= 8) these checks are exact: the draw is uniform over the bundles the window leaves, a path
// never reuses a bundle within 9 segments, and a path of K <= 8 bundles ends once it has drawn
// them all (drawing on would repeat one: at K = 1..3 a fixed cycle whose weights diverge).
#include <modes/multibounce/MultibounceShared.h>

#include <gtest/gtest.h>
#include <random>
#include <vector>

using namespace bl::shader;

namespace {

// Every k the draw returns for u on an n-point midpoint grid of [0, 1).
std::vector<std::uint32_t> counts(const MultibounceBundleWindow& w, std::uint32_t slots, std::uint32_t n) {
    std::vector<std::uint32_t> c(slots, 0);
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t k = blMultibouncePickBundle(w, (float(i) + 0.5f) / float(n), slots);
        EXPECT_LT(k, slots);
        if (k < slots) ++c[k];
    }
    return c;
}

} // namespace

// Uniform over the bundles not in the window, none of those in it, whatever their order.
TEST(MultibounceBundleSequence, DrawIsUniformOverTheUnusedBundles) {
    for (std::uint32_t slots : {2u, 3u, 4u, 9u, 16u, 64u}) {
        MultibounceBundleWindow w = blMultibounceBundleWindow(slots, true);
        EXPECT_EQ(w.size, std::min(kMultibounceRecentBundles, slots));
        std::mt19937 rng(slots);
        for (std::uint32_t step = 0; step < 20 && blMultibounceBundleLeft(w, slots); ++step) {
            const std::uint32_t available = slots - w.count;
            const std::uint32_t perBundle = 64;
            const std::vector<std::uint32_t> c = counts(w, slots, available * perBundle);
            for (std::uint32_t k = 0; k < slots; ++k) {
                bool used = false;
                for (std::uint32_t i = 0; i < w.count; ++i) used = used || w.bundles[i] == k;
                // The grid puts exactly perBundle points in each of the `available` equal intervals
                // (float rounding at an interval's edge can move one).
                if (used) {
                    EXPECT_EQ(c[k], 0u) << "K " << slots << ", bundle " << k << " drawn again";
                } else {
                    EXPECT_NEAR(double(c[k]), double(perBundle), 1.0) << "K " << slots << ", bundle " << k;
                }
            }
            blMultibounceRemember(w, blMultibouncePickBundle(w, std::uniform_real_distribution<float>(0, 1)(rng), slots));
        }
    }
}

// Along a path the last 8 bundles are never drawn again, never the one arrived by; a path of
// K <= 8 bundles draws each once and then has none left (it ends), one of more bundles never runs out.
TEST(MultibounceBundleSequence, PathsNeverReuseARecentBundle) {
    for (std::uint32_t slots : {1u, 2u, 5u, 8u, 9u, 64u}) {
        MultibounceBundleWindow w = blMultibounceBundleWindow(slots, true);
        std::mt19937 rng(7);
        std::vector<std::uint32_t> path;
        for (int segment = 0; segment < 200; ++segment) {
            if (!blMultibounceBundleLeft(w, slots)) break;
            // u just below 1 as well: the largest draw must stay in range.
            const float u = segment % 10 == 9 ? 0.99999994f : std::uniform_real_distribution<float>(0, 1)(rng);
            const std::uint32_t k = blMultibouncePickBundle(w, u, slots);
            ASSERT_LT(k, slots);
            for (std::size_t back = 1; back <= kMultibounceRecentBundles && back <= path.size(); ++back) {
                EXPECT_NE(path[path.size() - back], k) << "K " << slots << ": segment " << segment << " reuses the bundle of "
                                                       << back << " segments before";
            }
            path.push_back(k);
            blMultibounceRemember(w, k);
        }
        const std::size_t expected = slots <= kMultibounceRecentBundles ? slots : 200;
        EXPECT_EQ(path.size(), expected) << "K " << slots << ": bundles drawn before the path has none left";
    }
}

// Halton directions (stratified within an iteration) keep the draw over all K: no window.
TEST(MultibounceBundleSequence, StratifiedDirectionsDrawOverAllBundles) {
    MultibounceBundleWindow w = blMultibounceBundleWindow(16, false);
    EXPECT_EQ(w.size, 0u);
    EXPECT_TRUE(blMultibounceBundleLeft(w, 16));
    blMultibounceRemember(w, 3);
    EXPECT_EQ(w.count, 0u);
    const std::vector<std::uint32_t> c = counts(w, 16, 16 * 64);
    for (std::uint32_t k = 0; k < 16; ++k) EXPECT_NEAR(double(c[k]), 64.0, 1.0) << "bundle " << k;
}
