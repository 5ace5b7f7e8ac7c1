#include "bundle/DirectionSampler.h"

#include "base/Error.h"
#include "sampling/Halton.h"

#include <cmath>
#include <shared/Random.h>
#include <shared/Sampling.h>

namespace bl {

DirectionSequence directionSequenceNamed(std::string_view name) {
    if (name == "random") return DirectionSequence::Random;
    if (name == "stratified") return DirectionSequence::Stratified;
    if (name == "importance") return DirectionSequence::Importance;
    return DirectionSequence::Halton;
}

namespace {
constexpr float kUniformSpherePdf = 1.0f / (4.0f * shader::kPi);
constexpr float kOneBelow = 0x1.fffffep-1f; // the largest float below 1
}

DirectionSampler::DirectionSampler(DirectionSequence sequence, std::uint32_t seed, std::uint32_t strata,
                                   const EnvironmentLight* environment, float offset)
    : mSequence(sequence), mSeed(seed), mStrata(std::max(strata, 1u)), mEnvironment(environment) {
    if (sequence == DirectionSequence::Importance) {
        if (!environment || !environment->present()) {
            throw Error("importance-sampled bundle directions need an environment");
        }
        if (!(offset >= 0.0f)) {
            throw Error("importance offset must be >= 0");
        }
        // q = (L + L_o) / (E + 4 pi L_o) with E = integral of L and L_o = offset * E / (4 pi):
        // a mixture of the luminance sampler (weight E / (E + 4 pi L_o)) and uniform directions.
        mEnvironmentProbability = 1.0f / (1.0f + offset);
    }
}

glm::vec2 DirectionSampler::unitSquare(std::uint32_t index) const {
    switch (mSequence) {
    case DirectionSequence::Random:
        return {shader::blHashRandom(mSeed, 2 * index), shader::blHashRandom(mSeed, 2 * index + 1)};
    case DirectionSequence::Stratified: {
        const auto side = static_cast<std::uint32_t>(std::max(1.0, std::floor(std::sqrt(double(mStrata)))));
        const std::uint32_t cell = index % (side * side);
        const glm::vec2 jitter(shader::blHashRandom(mSeed, 2 * index), shader::blHashRandom(mSeed, 2 * index + 1));
        return (glm::vec2(float(cell % side), float(cell / side)) + jitter) / float(side);
    }
    default: {
        // Halton in bases kBundleDirectionBases (5, 7: not the camera jitter's, so the two stay
        // independent), with a Cranley-Patterson rotation per seed (seed 0: the plain sequence).
        glm::vec2 shift = mSeed ? glm::vec2(shader::blHashRandom(mSeed, 0x7f4a7c15u), shader::blHashRandom(mSeed, 0x1b873593u))
                                : glm::vec2(0.0f);
        glm::vec2 p(float(radicalInverse(kBundleDirectionBases[0], index + 1)),
                    float(radicalInverse(kBundleDirectionBases[1], index + 1)));
        p += shift;
        return p - glm::floor(p);
    }
    }
}

BundleDirection DirectionSampler::sample(std::uint32_t index) const {
    BundleDirection d;
    glm::vec2 u = unitSquare(index);
    d.rotation = shader::kTwoPi * shader::blHashRandom(mSeed ^ 0x9e3779b9u, index);
    if (mSequence == DirectionSequence::Importance) {
        // The point's first coordinate picks the mixture component and is stretched back over
        // [0, 1): each component gets a stratified share of the points. (A hash of its own per
        // direction handed each component a random subset: i.i.d.-like error,
        // DirectionSampler.ImportanceDirectionsStayStratified.)
        float pdfIgnored = 0.0f;
        const float p = mEnvironmentProbability;
        if (u.x < p) {
            d.omega = mEnvironment->sample({std::min(u.x / p, kOneBelow), u.y}, &pdfIgnored);
        } else {
            d.omega = shader::blSampleUniformSphere({std::min((u.x - p) / (1.0f - p), kOneBelow), u.y});
        }
        return d;
    }
    d.omega = shader::blSampleUniformSphere(u);
    return d;
}

float DirectionSampler::pdf(const glm::vec3& omega) const {
    if (mSequence != DirectionSequence::Importance) {
        return kUniformSpherePdf;
    }
    return mEnvironmentProbability * mEnvironment->pdf(omega) + (1.0f - mEnvironmentProbability) * kUniformSpherePdf;
}

} // namespace bl
