// Bundle directions on the sphere, with their densities ([RB 3] and [TO12 Eq. 2], papers/EQUATIONS.md).
//
// A bundle direction omega serves both omega and -omega; a point with normal n uses the one in
// its hemisphere, whose density among that hemisphere's directions is
//   p_r(d) = q(d) + q(-d)                        (q: density of the bundle directions on the sphere)
// = 1 / (2 pi) for uniform directions, and for environment importance ([TO12] Eq. 2)
//   q(w) = (L(w) + L_o) / integral (L + L_o),  so  p_r(d) = (L(d) + L(-d) + 2 L_o) / integral (L + L_o)
// with L the environment's luminance (its importance sampler's density) and L_o >= 0 an offset
// that keeps every direction (indirect light) sampled.
#pragma once

#include "sampling/EnvironmentLight.h"

#include <glm/glm.hpp>

#include <string_view>

namespace bl {

enum class DirectionSequence { Halton, Random, Stratified, Importance };
// The sequence a `directions` setting names: "random", "stratified", "importance", else Halton.
DirectionSequence directionSequenceNamed(std::string_view name);

struct BundleDirection {
    glm::vec3 omega{0, 0, 1};
    float rotation = 0.0f; // radians about omega, for the frame
};

class DirectionSampler {
public:
    // `strata`: directions per stratified pass (a sqrt(n) x sqrt(n) grid, cycled). `environment`
    // and `offset` (L_o as a fraction of the mean environment luminance) matter for Importance.
    DirectionSampler(DirectionSequence sequence, std::uint32_t seed, std::uint32_t strata = 256,
                     const EnvironmentLight* environment = nullptr, float offset = 0.1f);

    // The index-th direction: deterministic in (sequence, seed, index).
    BundleDirection sample(std::uint32_t index) const;
    // q(omega): density on the sphere.
    float pdf(const glm::vec3& omega) const;
    // p_r(d) = q(d) + q(-d): density of d among the directions a point in d's hemisphere uses.
    float hemispherePdf(const glm::vec3& d) const { return pdf(d) + pdf(-d); }
    // The two numbers in [0, 1)^2 the index-th direction is made from (tests check that they are
    // independent of the camera's pixel jitter, core/sampling/PixelSamples.h).
    glm::vec2 unitSquare(std::uint32_t index) const;

private:

    DirectionSequence mSequence;
    std::uint32_t mSeed;
    std::uint32_t mStrata;
    const EnvironmentLight* mEnvironment;
    float mEnvironmentProbability = 0.0f; // mixture weight of the luminance-sampled component
};

} // namespace bl
