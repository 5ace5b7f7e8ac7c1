// Pearson's chi-square goodness-of-fit test of a sampler against its density (Mitsuba's chi2,
// pbrt's bsdfs_test): bins with fewer than 5 expected samples are pooled; the p-value comes from
// the regularized upper incomplete gamma function.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace bl::test {

// Q(a, x) = Gamma(a, x) / Gamma(a).
double regularizedGammaQ(double a, double x);

struct ChiSquareResult {
    double statistic = 0.0;
    int degreesOfFreedom = 0;
    double pValue = 1.0;
    std::string describe() const;
};

// observed[i] counts samples in bin i, expected[i] their expected number (same total or less:
// the rest went to no bin, e.g. rejected samples).
ChiSquareResult chiSquareTest(const std::vector<double>& observed, const std::vector<double>& expected);

} // namespace bl::test
