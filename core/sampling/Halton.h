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

// Which Halton dimensions each user draws from. A progressive iteration k samples one integrand
// over (pixel footprint x bundle direction); the k-th point of the 4D Halton sequence (2, 3, 5, 7)
// keeps its four numbers independent. Two users sharing a base would be correlated: with base 2
// in both, jitter.x equalled the direction's u.x in every even iteration.
inline constexpr std::uint32_t kPixelJitterBases[2] = {2, 3};
inline constexpr std::uint32_t kBundleDirectionBases[2] = {5, 7};

} // namespace bl
