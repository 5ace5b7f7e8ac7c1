// The progressive pixel jitter (core/sampling/PixelSamples.h): seed 0 keeps its centre-first
// sequence; other seeds shift it, each differently, and every shift still covers the pixel evenly.
#include "sampling/PixelSamples.h"

#include <gtest/gtest.h>

#include <set>
#include <utility>

using namespace bl;

TEST(PixelSamples, SeedZeroStartsAtTheCentre) {
    EXPECT_EQ(pixelSamplePosition(0, true, 0), glm::vec2(0.5f));
    EXPECT_EQ(pixelSamplePosition(1, true, 0), glm::vec2(0.0f, 0.5f + 1.0f / 3.0f)); // (1/2, 1/3) + 1/2
    EXPECT_EQ(pixelSamplePosition(5, false, 7), glm::vec2(0.5f)); // no jitter: the centre, any seed
}

TEST(PixelSamples, SeedsShiftTheSequenceDifferently) {
    std::set<std::pair<float, float>> shifts;
    for (std::uint64_t seed = 0; seed < 64; ++seed) {
        const glm::vec2 s = pixelSampleShift(seed);
        EXPECT_GE(s.x, 0.0f);
        EXPECT_LT(s.x, 1.0f);
        EXPECT_GE(s.y, 0.0f);
        EXPECT_LT(s.y, 1.0f);
        shifts.insert({s.x, s.y});
    }
    EXPECT_EQ(shifts.size(), 64u);
}

// A shift keeps the Halton points' strata (a shifted grid is a grid): of the first 16 points, 8 in
// each half of the pixel in x (base 2), and of the first 9, 3 in each third in y (base 3), for
// every seed.
TEST(PixelSamples, EveryShiftKeepsTheStrata) {
    for (std::uint64_t seed : {0ull, 1ull, 2ull, 12345ull}) {
        int halves[2] = {}, thirds[3] = {};
        for (std::uint32_t k = 0; k < 16; ++k) {
            const glm::vec2 p = pixelSamplePosition(k, true, seed);
            ASSERT_GE(p.x, 0.0f);
            ASSERT_LT(p.x, 1.0f);
            ASSERT_GE(p.y, 0.0f);
            ASSERT_LT(p.y, 1.0f);
            ++halves[int(p.x * 2.0f)];
            if (k < 9) ++thirds[int(p.y * 3.0f)];
        }
        EXPECT_EQ(halves[0], 8) << "seed " << seed;
        for (int c : thirds) EXPECT_EQ(c, 3) << "seed " << seed;
    }
}
