#include "image/Metrics.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

using namespace bl;
using bl::test::errorOf;

TEST(Metrics, KnownValues) {
    Image ref(16, 16, glm::vec3(1.0f)), test(16, 16, glm::vec3(1.0f));
    test.at(0, 0) = glm::vec3(2.0f); // one pixel off by +1 in every channel
    ImageMetrics m = computeMetrics(test, ref);
    const double n = 256.0;
    EXPECT_DOUBLE_EQ(m.mse, 1.0 / n);
    EXPECT_DOUBLE_EQ(m.rmse, std::sqrt(1.0 / n));
    EXPECT_NEAR(m.relMse, 1.0 / 1.01 / n, 1e-12);
    EXPECT_NEAR(m.smape, 2.0 / 3.0 / n, 1e-12);
    EXPECT_DOUBLE_EQ(m.mae, 1.0 / n);
    EXPECT_NEAR(m.meanRatio.x, (n + 1.0) / n, 1e-12);
    ASSERT_EQ(m.blockRatios.blocks, 4u);
    EXPECT_NEAR(m.blockRatios.maxDeviation, 1.0 / 64.0, 1e-12);
    EXPECT_NEAR(m.blockRatios.rms, std::sqrt((1.0 / 64.0) * (1.0 / 64.0) / 4.0), 1e-12);
    ImageMetrics same = computeMetrics(ref, ref);
    EXPECT_EQ(same.mse, 0.0);
    EXPECT_EQ(same.smape, 0.0);
    EXPECT_DOUBLE_EQ(same.blockRatios.mean, 1.0);
}

TEST(Metrics, DownsamplingMatchesResolutions) {
    Image big(8, 4), small(4, 2);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) big.at(x, y) = glm::vec3(float(x + 8 * y));
    Image half = boxDownsample(big, 2);
    EXPECT_FLOAT_EQ(half.at(0, 0).x, (0 + 1 + 8 + 9) / 4.0f);
    Image a = big, b = small;
    matchResolution(a, b);
    EXPECT_EQ(a.width(), 4);
    Image odd(6, 4);
    EXPECT_NE(errorOf([&] { Image x = big; matchResolution(x, odd); }).find("no integer factor"), std::string::npos);
    EXPECT_NE(errorOf([&] { computeMetrics(big, small); }).find("differ in size"), std::string::npos);
}

TEST(Metrics, ErrorMaps) {
    Image ref(4, 4, glm::vec3(1.0f)), test(4, 4, glm::vec3(1.0f));
    test.at(1, 1) = glm::vec3(2.0f);
    std::vector<float> ratio = errorValues(test, ref, "ratio");
    EXPECT_FLOAT_EQ(ratio[5], 1.0f); // log2(2)
    EXPECT_FLOAT_EQ(ratio[0], 0.0f);
    Image map = falseColour(ratio, 4, 4, true, 1.0f);
    EXPECT_EQ(map.at(0, 0), glm::vec3(1.0f)); // zero: white on the diverging map
    EXPECT_GT(map.at(1, 1).x, map.at(1, 1).z); // positive: red
    EXPECT_NE(errorOf([&] { errorValues(test, ref, "psnr"); }).find("unknown error map"), std::string::npos);
}
