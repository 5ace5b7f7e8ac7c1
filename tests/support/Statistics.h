// The statistics every estimator test uses, so that each one says the same thing the same way:
// independent runs (seeds), the mean over them with its standard error, Student-t quantiles for
// the few runs a test can afford, a noise gate (a test whose noise is as large as its tolerance
// cannot fail for the bias it claims to catch), paired comparisons on common random numbers,
// strategy-against-strategy checks that need no reference, and per-region tests whose family-wise
// false-failure rate is corrected for the number of regions (Holm).
//
// The hypothesis each check tests: the estimator's expectation lies within `tolerance` of the
// reference (tolerance = the bias the test allows: 0 for an unbiased estimator against an exact
// value, a derived bound for a stated approximation). It fails when the seeds' mean lies further
// than tolerance + t(1 - alpha/2, n - 1) * stderr from the reference, so a correct estimator fails
// with probability at most alpha (per family of regions after the correction), and a bias of
// tolerance + 2 t stderr is caught almost surely. The noise gate (stderr <= tolerance / 3) keeps
// that detectable bias within a small multiple of the tolerance; a run too noisy for its tolerance
// fails with "too noisy to test" and the numbers, never passes quietly.
#pragma once

#include "image/Image.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace bl::test::stats {

// Family-wise false-failure rate of a check (one check, or all regions of one layer together).
// The seeds are fixed, so a test is deterministic: alpha is the chance that a correct change to
// an estimator (new random numbers, same expectation) trips a given check. 1% per check; smaller
// rates cost seeds (t(1 - alpha / 2, n - 1) grows fast below 8 seeds).
constexpr double kAlpha = 0.01;
// The noise gate: the standard error of the seeds' mean at most this share of the tolerance.
constexpr double kNoiseGate = 1.0 / 3.0;

// `count` seeds starting at `first` (seed 0 is left out: some modes read it as "unseeded").
std::vector<std::uint32_t> seeds(std::size_t count, std::uint32_t first = 1);

// Student's t distribution with `dof` degrees of freedom (any positive real): the CDF, and its
// inverse by bisection on the CDF (monotone; the incomplete beta function, Numerical Recipes'
// continued fraction, gives the CDF to ~1e-14).
double regularizedIncompleteBeta(double a, double b, double x);
double studentTCdf(double t, double dof);
double studentTQuantile(double p, double dof);
// Two-sided critical value: P(|T| > t) = alpha.
double studentTCritical(double alpha, double dof);

// Mean, sample standard deviation and standard error of the mean of independent values.
struct Summary {
    std::size_t n = 0;
    double mean = 0.0;
    double stddev = 0.0;
    double stderr_ = 0.0;
};
Summary summarize(const std::vector<double>& values);

// The noise gate: stderr <= kNoiseGate * tolerance, else "too noisy to test" with the numbers.
::testing::AssertionResult quietEnough(const Summary& s, double tolerance, const std::string& what);

// |mean - reference| <= tolerance + t(1 - alpha/2, n - 1) stderr, behind the noise gate.
::testing::AssertionResult agrees(const Summary& s, double reference, double tolerance, const std::string& what,
                                  double alpha = kAlpha);

// The two-sided p-value of "expectation within `tolerance` of `reference`" (1 when the mean is
// inside; for the correction over regions).
double pValue(const Summary& s, double reference, double tolerance);

// Paired comparison on common random numbers: a[i] and b[i] from the same seed i; the difference
// a - b is summarized (the noise the two share cancels) and must lie within `tolerance` of
// `expected` (0: the same expectation).
Summary pairedDifference(const std::vector<double>& a, const std::vector<double>& b);
::testing::AssertionResult pairedAgree(const std::vector<double>& a, const std::vector<double>& b, double expected,
                                       double tolerance, const std::string& what, double alpha = kAlpha);

// Two strategies that estimate the same integral, without a reference: per seed the image (or
// region) values of each, compared as a paired difference against zero with a tolerance relative
// to their common mean.
::testing::AssertionResult strategiesAgree(const std::vector<double>& a, const std::vector<double>& b,
                                           double relativeTolerance, const std::string& what, double alpha = kAlpha);

// Mean luminance (Rec. 709) of each block x block region of an image, row-major; a partial last
// row or column of blocks averages the pixels it has.
std::vector<double> blockMeans(const Image& image, int block);
double luminance(const glm::vec3& c);

// Per-region test: perSeed[s][r] is seed s's value of region r, reference[r] the reference's.
// Each region is held to relativeTolerance * max(reference[r], dimFloor * mean region) (a region
// with 5% of the mean's light matters to the image as the mean region does at 1/20 of its error),
// behind the noise gate, and the family of regions is corrected by Holm's step-down procedure at
// family-wise rate alpha. Prints one line per region (value, stderr, reference, error).
struct RegionOptions {
    double relativeTolerance = 0.05;
    double dimFloor = 0.0;
    double alpha = kAlpha;
};
::testing::AssertionResult regionsAgree(const std::vector<std::vector<double>>& perSeed,
                                        const std::vector<double>& reference, const RegionOptions& options,
                                        const std::string& what);

// Per-region paired comparison of two estimators on common random numbers (a[s][r] and b[s][r]
// from the same seed s): per region the difference a - b against 0, with a tolerance of
// relativeTolerance times b's region mean (floored as above), Holm-corrected, behind the gate.
::testing::AssertionResult pairedRegionsAgree(const std::vector<std::vector<double>>& a,
                                              const std::vector<std::vector<double>>& b, const RegionOptions& options,
                                              const std::string& what);

// Holm's step-down procedure: which of the hypotheses with these p-values are rejected at
// family-wise rate alpha (Bonferroni's alpha / m for the smallest, alpha / (m - 1) next, ...).
std::vector<bool> holmRejects(const std::vector<double>& pValues, double alpha);

} // namespace bl::test::stats
