// The fitting bundle build's refusal (core/bundle/FittingBuild.h): one text for every mode, naming
// what would fit. The build loop itself runs in every bundle mode's tests (a pool that starts small
// grows: bundle_rebuilds; Multibounce.RefusesBundlesBeyondTheMemoryCap refuses).
#include "bundle/FittingBuild.h"

#include <gtest/gtest.h>

using namespace bl;

TEST(FittingBuild, RefusalNamesTheBundleCountThatFits) {
    // 64 bundles asked for 4x the nodes the pool may hold: 16 would fit.
    const std::string text = fittingBuildRefusal({"multibounce", 64, 256}, 4'000'000, 1'000'000, 16);
    EXPECT_NE(text.find("multibounce: 64 bundles of 256^2 pixels need 4000000 nodes"), std::string::npos) << text;
    EXPECT_NE(text.find("holds at most 1000000"), std::string::npos) << text;
    EXPECT_NE(text.find("memory_cap_mib"), std::string::npos) << text;
    EXPECT_NE(text.find("about 16 bundles fit at this resolution, or all 64 at bundle_resolution of about 128"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("61.0 MiB"), std::string::npos) << text; // 4e6 nodes of 16 bytes
}

TEST(FittingBuild, OneBundleThatDoesNotFitNamesAResolution) {
    // One bundle of 513^2 pixels asked for 4x the limit: half the side, 256, would fit.
    const std::string text = fittingBuildRefusal({"atlas", 1, 513}, 4'000'000, 1'000'000, 16);
    EXPECT_NE(text.find("atlas: 1 bundle of 513^2 pixels needs 4000000 nodes"), std::string::npos) << text;
    EXPECT_NE(text.find("lower bundle_resolution (about 256 would fit)"), std::string::npos) << text;
    // Many bundles of which not even one fits: the resolution too.
    const std::string many = fittingBuildRefusal({"bidir", 8, 512}, 80'000'000, 1'000'000, 16);
    EXPECT_NE(many.find("lower bundle_resolution (about 57 would fit)"), std::string::npos) << many;
}
