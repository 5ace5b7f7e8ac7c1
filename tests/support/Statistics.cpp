#include "support/Statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>

namespace bl::test::stats {

std::vector<std::uint32_t> seeds(std::size_t count, std::uint32_t first) {
    std::vector<std::uint32_t> s(count);
    std::iota(s.begin(), s.end(), first);
    return s;
}

namespace {

// Continued fraction of the incomplete beta function (Numerical Recipes 6.4, modified Lentz).
double betaContinuedFraction(double a, double b, double x) {
    constexpr double kTiny = 1e-300, kEpsilon = 1e-15;
    const double qab = a + b, qap = a + 1.0, qam = a - 1.0;
    double c = 1.0, d = 1.0 - qab * x / qap;
    d = 1.0 / (std::abs(d) < kTiny ? kTiny : d);
    double h = d;
    for (int m = 1; m <= 10000; ++m) {
        const double m2 = 2.0 * m;
        double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
        d = 1.0 + aa * d;
        d = 1.0 / (std::abs(d) < kTiny ? kTiny : d);
        c = 1.0 + aa / c;
        c = std::abs(c) < kTiny ? kTiny : c;
        h *= d * c;
        aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
        d = 1.0 + aa * d;
        d = 1.0 / (std::abs(d) < kTiny ? kTiny : d);
        c = 1.0 + aa / c;
        c = std::abs(c) < kTiny ? kTiny : c;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1.0) < kEpsilon) break;
    }
    return h;
}

} // namespace

double regularizedIncompleteBeta(double a, double b, double x) {
    if (x <= 0.0) return 0.0;
    if (x >= 1.0) return 1.0;
    const double logFront =
        std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
    // The continued fraction converges fast for x < (a + 1) / (a + b + 2); use the symmetry beyond.
    if (x < (a + 1.0) / (a + b + 2.0)) return std::exp(logFront) * betaContinuedFraction(a, b, x) / a;
    return 1.0 - std::exp(logFront) * betaContinuedFraction(b, a, 1.0 - x) / b;
}

namespace {

// P(T > t) for t >= 0, without the cancellation of 1 - CDF (tails to 1e-300 stay exact).
double upperTail(double t, double dof) {
    return 0.5 * regularizedIncompleteBeta(0.5 * dof, 0.5, dof / (dof + t * t));
}

} // namespace

double studentTCdf(double t, double dof) {
    const double tail = upperTail(std::abs(t), dof);
    return t >= 0.0 ? 1.0 - tail : tail;
}

double studentTQuantile(double p, double dof) {
    if (!(p > 0.0 && p < 1.0) || !(dof > 0.0)) return std::nan("");
    if (p == 0.5) return 0.0;
    // Solve P(T > t) = q for the smaller tail q (so p = 1e-9 keeps its digits), then the sign.
    const double q = std::min(p, 1.0 - p);
    // Bracket: t doubles until the tail falls below q (Cauchy's, the heaviest at dof >= 1, needs
    // t ~ 1 / (pi q)), then bisection to double precision (the tail is monotone).
    double lo = 0.0, hi = 1.0;
    while (upperTail(hi, dof) > q && hi < 1e300) {
        lo = hi;
        hi *= 2.0;
    }
    for (int i = 0; i < 2000 && hi - lo > 4e-16 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (upperTail(mid, dof) > q ? lo : hi) = mid;
    }
    const double t = 0.5 * (lo + hi);
    return p > 0.5 ? t : -t;
}

double studentTCritical(double alpha, double dof) { return studentTQuantile(1.0 - 0.5 * alpha, dof); }

Summary summarize(const std::vector<double>& values) {
    Summary s;
    s.n = values.size();
    if (s.n == 0) return s;
    double sum = 0.0;
    for (double v : values) sum += v;
    s.mean = sum / double(s.n);
    if (s.n < 2) {
        // One run has no spread to measure: infinite error, so the noise gate refuses it.
        s.stddev = s.stderr_ = INFINITY;
        return s;
    }
    double squares = 0.0;
    for (double v : values) squares += (v - s.mean) * (v - s.mean);
    s.stddev = std::sqrt(squares / double(s.n - 1));
    s.stderr_ = s.stddev / std::sqrt(double(s.n));
    return s;
}

namespace {

std::string describe(const Summary& s, double reference, double tolerance) {
    char line[256];
    std::snprintf(line, sizeof line, "mean %.6g +- %.3g (stderr, %zu seeds), reference %.6g (%+.3g, %+.2f%%), "
                  "tolerance %.3g",
                  s.mean, s.stderr_, s.n, reference, s.mean - reference,
                  reference != 0.0 ? 100.0 * (s.mean / reference - 1.0) : 0.0, tolerance);
    return line;
}

} // namespace

::testing::AssertionResult quietEnough(const Summary& s, double tolerance, const std::string& what) {
    if (s.n >= 2 && std::isfinite(s.mean) && s.stderr_ <= kNoiseGate * tolerance) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << what << ": too noisy to test: stderr " << s.stderr_ << " over " << s.n
                                         << " seeds, above " << kNoiseGate << " x tolerance " << tolerance
                                         << " (more seeds, or a tolerance the estimator can resolve)";
}

::testing::AssertionResult agrees(const Summary& s, double reference, double tolerance, const std::string& what,
                                  double alpha) {
    if (auto gate = quietEnough(s, tolerance, what); !gate) return gate;
    const double window = tolerance + studentTCritical(alpha, double(s.n - 1)) * s.stderr_;
    if (std::abs(s.mean - reference) <= window) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << what << ": " << describe(s, reference, tolerance) << ": off by more than "
                                         << window << " (tolerance + t(" << 1.0 - 0.5 * alpha << ", " << s.n - 1
                                         << ") stderr)";
}

double pValue(const Summary& s, double reference, double tolerance) {
    const double excess = std::abs(s.mean - reference) - tolerance;
    if (excess <= 0.0) return 1.0;
    if (!(s.stderr_ > 0.0)) return 0.0;
    return 2.0 * (1.0 - studentTCdf(excess / s.stderr_, double(s.n - 1)));
}

Summary pairedDifference(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> d;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) d.push_back(a[i] - b[i]);
    return summarize(d);
}

::testing::AssertionResult pairedAgree(const std::vector<double>& a, const std::vector<double>& b, double expected,
                                       double tolerance, const std::string& what, double alpha) {
    if (a.size() != b.size()) {
        return ::testing::AssertionFailure() << what << ": " << a.size() << " and " << b.size()
                                             << " seeds: a paired comparison needs the same seeds";
    }
    return agrees(pairedDifference(a, b), expected, tolerance, what + " (paired difference)", alpha);
}

::testing::AssertionResult strategiesAgree(const std::vector<double>& a, const std::vector<double>& b,
                                           double relativeTolerance, const std::string& what, double alpha) {
    const double scale = 0.5 * std::abs(summarize(a).mean + summarize(b).mean);
    return pairedAgree(a, b, 0.0, relativeTolerance * scale, what, alpha);
}

double luminance(const glm::vec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

std::vector<double> blockMeans(const Image& image, int block) {
    const int bx = (image.width() + block - 1) / block, by = (image.height() + block - 1) / block;
    std::vector<double> sum(std::size_t(bx * by), 0.0), count(sum.size(), 0.0);
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            const std::size_t r = std::size_t((y / block) * bx + x / block);
            sum[r] += luminance(image.at(x, y));
            count[r] += 1.0;
        }
    }
    for (std::size_t r = 0; r < sum.size(); ++r) sum[r] /= count[r];
    return sum;
}

std::vector<bool> holmRejects(const std::vector<double>& pValues, double alpha) {
    std::vector<std::size_t> order(pValues.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return pValues[i] < pValues[j]; });
    std::vector<bool> rejected(pValues.size(), false);
    const std::size_t m = pValues.size();
    for (std::size_t k = 0; k < m; ++k) {
        if (pValues[order[k]] > alpha / double(m - k)) break; // every larger p-value is kept too
        rejected[order[k]] = true;
    }
    return rejected;
}

::testing::AssertionResult regionsAgree(const std::vector<std::vector<double>>& perSeed,
                                        const std::vector<double>& reference, const RegionOptions& options,
                                        const std::string& what) {
    const std::size_t regions = reference.size();
    double meanRegion = 0.0;
    for (double r : reference) meanRegion += r / double(regions);
    std::vector<Summary> summaries;
    std::vector<double> tolerances, pValues;
    std::ostringstream failures;
    bool noisy = false;
    for (std::size_t r = 0; r < regions; ++r) {
        std::vector<double> values;
        for (const auto& seed : perSeed) values.push_back(seed.at(r));
        summaries.push_back(summarize(values));
        tolerances.push_back(options.relativeTolerance * std::max(reference[r], options.dimFloor * meanRegion));
        pValues.push_back(pValue(summaries[r], reference[r], tolerances[r]));
        std::printf("%s region %2zu: %s, p %.2g\n", what.c_str(), r,
                    describe(summaries[r], reference[r], tolerances[r]).c_str(), pValues[r]);
        if (auto gate = quietEnough(summaries[r], tolerances[r], what + " region " + std::to_string(r)); !gate) {
            failures << gate.message() << "\n";
            noisy = true;
        }
    }
    const std::vector<bool> rejected = holmRejects(pValues, options.alpha);
    bool off = false;
    for (std::size_t r = 0; r < regions; ++r) {
        if (!rejected[r]) continue;
        off = true;
        failures << what << " region " << r << ": " << describe(summaries[r], reference[r], tolerances[r])
                 << ": p = " << pValues[r] << ", rejected by Holm's procedure over " << regions
                 << " regions at family-wise alpha " << options.alpha << "\n";
    }
    if (!noisy && !off) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << failures.str();
}

::testing::AssertionResult pairedRegionsAgree(const std::vector<std::vector<double>>& a,
                                              const std::vector<std::vector<double>>& b, const RegionOptions& options,
                                              const std::string& what) {
    if (a.size() != b.size() || a.empty()) {
        return ::testing::AssertionFailure() << what << ": " << a.size() << " and " << b.size()
                                             << " seeds: a paired comparison needs the same seeds";
    }
    // b's seed mean per region is the scale; a_s - b_s + mean(b) has the paired difference's
    // spread about that mean, so the region test of it is the paired test.
    std::vector<double> scale(b.front().size(), 0.0);
    for (const auto& seed : b)
        for (std::size_t r = 0; r < scale.size(); ++r) scale[r] += seed.at(r) / double(b.size());
    std::vector<std::vector<double>> shifted = a;
    for (std::size_t s = 0; s < a.size(); ++s)
        for (std::size_t r = 0; r < scale.size(); ++r) shifted[s].at(r) = a[s].at(r) - b[s].at(r) + scale[r];
    return regionsAgree(shifted, scale, options, what + " (paired difference)");
}

} // namespace bl::test::stats
