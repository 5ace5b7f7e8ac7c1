// Where inside its pixel the k-th sample of a progressive rasterizer lands: a Halton sequence in
// bases kPixelJitterBases (2, 3) under a Cranley-Patterson shift. Iterating converges to the
// box-filtered pixel (CONVENTIONS.md).
//
// Seed 0 shifts by 1/2, so its k = 0 is the pixel centre (one-iteration renders and previews
// sample centres). Any other seed shifts by a point hashed from the seed: a randomized QMC jitter,
// so that renders with different seeds integrate the pixel footprint differently and their spread
// sees the footprint's integration error (with one shift for every seed, a narrow highlight's
// quadrature error was the same in every seed, invisible to the seed spread, and read as bias
// against the reference: stress phong-* blocks 13-29% of the image mean).
#pragma once

#include "sampling/Halton.h"

#include <cstdint>

#include <glm/glm.hpp>

namespace bl {

// The shift of `seed`'s jitter sequence (in [0, 1)^2).
inline glm::vec2 pixelSampleShift(std::uint64_t seed) {
    if (seed == 0) {
        return glm::vec2(0.5f);
    }
    // SplitMix64 of the seed: two independent 24-bit fractions.
    std::uint64_t z = seed + 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return glm::vec2(float(z >> 40) * 0x1.0p-24f, float((z >> 8) & 0xffffffu) * 0x1.0p-24f);
}

inline glm::vec2 pixelSamplePosition(std::uint32_t k, bool jitter = true, std::uint64_t seed = 0) {
    if (!jitter) {
        return glm::vec2(0.5f);
    }
    glm::vec2 p(static_cast<float>(radicalInverse(kPixelJitterBases[0], k)),
                static_cast<float>(radicalInverse(kPixelJitterBases[1], k)));
    p += pixelSampleShift(seed);
    return p - glm::floor(p);
}

} // namespace bl
