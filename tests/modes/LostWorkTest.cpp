// The lost-work verdict every driver applies to a render's ImageSet (modes/LostWork.h).
#include "modes/Mode.h"

#include <gtest/gtest.h>

using namespace bl;

namespace {
ImageSet withSamples(std::uint64_t nonFinite, std::uint64_t dropped, std::uint64_t expected) {
    ImageSet s;
    addSampleLosses(s, nonFinite, dropped, expected);
    return s;
}
} // namespace

TEST(LostWork, NothingLostIsSilent) {
    const LostWorkVerdict v = judgeLostWork("raster", withSamples(0, 0, 64));
    EXPECT_TRUE(v.warnings.empty());
    EXPECT_EQ(v.refusal, "");
}

TEST(LostWork, EachCounterAboveZeroIsAWarningWithItsCount) {
    ImageSet s = withSamples(3, 5, 64);
    EXPECT_EQ(s.nonFiniteSamples, 3u);
    const LostWorkVerdict v = judgeLostWork("raster", s);
    ASSERT_EQ(v.warnings.size(), 2u);
    EXPECT_EQ(v.warnings[0], "raster: 3 samples of 64 refused as NaN or infinite (non_finite_samples)");
    EXPECT_EQ(v.warnings[1], "raster: 5 samples of 64 never added to their pixel (dropped_samples)");
    EXPECT_EQ(v.refusal, "");
}

// Counters of one unit are disjoint parts of one total: refused when together they are all of it.
TEST(LostWork, AllOfAUnitLostIsARefusal) {
    EXPECT_NE(judgeLostWork("raster", withSamples(64, 0, 64)).refusal, "");
    EXPECT_NE(judgeLostWork("raster", withSamples(0, 64, 64)).refusal, "");
    EXPECT_NE(judgeLostWork("raster", withSamples(40, 24, 64)).refusal, "");
    EXPECT_EQ(judgeLostWork("raster", withSamples(40, 23, 64)).refusal, "");
    ImageSet vpls = withSamples(0, 0, 64);
    vpls.lost.push_back({"non_finite_vpls", 16, 16, "VPLs", "were not finite and left out"});
    const LostWorkVerdict v = judgeLostWork("bidir", vpls);
    EXPECT_EQ(v.refusal.rfind("bidir: every one of its 16 VPLs was lost", 0), 0u) << v.refusal;
    vpls.lost.back().count = 15;
    EXPECT_EQ(judgeLostWork("bidir", vpls).refusal, "");
}

// Notes (e.g. every VPL escaped: zero samples, not lost work) are said after the lost work and
// never refuse an image.
TEST(LostWork, NotesAreWarningsNeverRefusals) {
    ImageSet s = withSamples(1, 0, 64);
    s.notes.push_back("all 8 VPLs carry no light");
    const LostWorkVerdict v = judgeLostWork("bidir", s);
    EXPECT_EQ(v.refusal, "");
    ASSERT_EQ(v.warnings.size(), 2u);
    EXPECT_EQ(v.warnings[1], "bidir: all 8 VPLs carry no light");
}

TEST(LostWork, UnknownOrEmptyTotalsAreNeverRefused) {
    ImageSet s = withSamples(0, 0, 0); // no sample asked for: nothing to judge
    EXPECT_EQ(judgeLostWork("raster", s).refusal, "");
    s.lost.push_back({"mismatches", 7, 0, "texels", "disagree"});
    const LostWorkVerdict v = judgeLostWork("bidir", s);
    EXPECT_EQ(v.refusal, "");
    ASSERT_EQ(v.warnings.size(), 1u);
    EXPECT_EQ(v.warnings[0], "bidir: 7 texels disagree (mismatches)");
}
