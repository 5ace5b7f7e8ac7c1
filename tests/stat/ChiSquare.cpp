#include "stat/ChiSquare.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace bl::test {

namespace {
// Series for P(a, x), valid for x < a + 1.
double gammaPSeries(double a, double x) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 10000; ++n) {
        term *= x / (a + n);
        sum += term;
        if (std::abs(term) < std::abs(sum) * 1e-15) break;
    }
    return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Continued fraction for Q(a, x) (modified Lentz), valid for x >= a + 1.
double gammaQFraction(double a, double x) {
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::abs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::abs(c) < tiny) c = tiny;
        d = 1.0 / d;
        double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1.0) < 1e-15) break;
    }
    return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}
} // namespace

double regularizedGammaQ(double a, double x) {
    if (x <= 0.0) return 1.0;
    return x < a + 1.0 ? 1.0 - gammaPSeries(a, x) : gammaQFraction(a, x);
}

std::string ChiSquareResult::describe() const {
    return "chi2 = " + std::to_string(statistic) + ", dof = " + std::to_string(degreesOfFreedom) +
           ", p = " + std::to_string(pValue);
}

ChiSquareResult chiSquareTest(const std::vector<double>& observed, const std::vector<double>& expected) {
    if (observed.size() != expected.size()) throw std::invalid_argument("chiSquareTest: size mismatch");
    // Pool the bins expected to hold fewer than 5 samples, and the samples in no bin.
    std::vector<std::pair<double, double>> bins; // (observed, expected)
    double pooledObserved = 0.0, pooledExpected = 0.0;
    for (std::size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 5.0) {
            pooledObserved += observed[i];
            pooledExpected += expected[i];
        } else {
            bins.emplace_back(observed[i], expected[i]);
        }
    }
    if (pooledExpected >= 5.0) {
        bins.emplace_back(pooledObserved, pooledExpected);
    } else if (pooledObserved > 10.0) {
        // Many samples where almost none are expected: the density is wrong there.
        return {1e30, 1, 0.0};
    }
    ChiSquareResult r;
    for (const auto& [o, e] : bins) r.statistic += (o - e) * (o - e) / e;
    r.degreesOfFreedom = static_cast<int>(bins.size()) - 1;
    r.pValue = regularizedGammaQ(0.5 * r.degreesOfFreedom, 0.5 * r.statistic);
    return r;
}

} // namespace bl::test
