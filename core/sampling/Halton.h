// Radical inverse / Halton sequence (deterministic low-discrepancy points).
#pragma once

#include <cstdint>

namespace bl {

// Radical inverse of `index` in `base`: the digits mirrored about the radix point, in [0, 1).
inline double radicalInverse(std::uint32_t base, std::uint64_t index) {
    const double inverseBase = 1.0 / base;
    double factor = inverseBase;
    double result = 0.0;
    while (index > 0) {
        result += static_cast<double>(index % base) * factor;
        index /= base;
        factor *= inverseBase;
    }
    return result;
}

} // namespace bl
