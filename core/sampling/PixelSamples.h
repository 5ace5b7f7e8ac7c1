// Where inside its pixel the k-th sample of a progressive rasterizer lands: the pixel centre
// first, then a Halton sequence in bases kPixelJitterBases (2, 3) shifted by 1/2 (a
// Cranley-Patterson rotation, so k = 0 is the centre). Iterating converges to the box-filtered pixel (CONVENTIONS.md).
#pragma once

#include "sampling/Halton.h"

#include <glm/glm.hpp>

namespace bl {

inline glm::vec2 pixelSamplePosition(std::uint32_t k, bool jitter = true) {
    if (!jitter || k == 0) {
        return glm::vec2(0.5f);
    }
    glm::vec2 p(static_cast<float>(radicalInverse(kPixelJitterBases[0], k)) + 0.5f,
                static_cast<float>(radicalInverse(kPixelJitterBases[1], k)) + 0.5f);
    return p - glm::floor(p);
}

} // namespace bl
