// The median of benchmark timings (the benchmarks report medians over repeats: shared machines
// are noisy).
#pragma once

#include <algorithm>
#include <vector>

namespace bl::cli {

inline double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

} // namespace bl::cli
