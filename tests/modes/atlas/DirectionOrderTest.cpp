// B1 of issue 19: the atlas's glossy transfer pairs each direction with the next, so the next must be
// independent of the current one for every direction sequence (modes/atlas/DirectionOrder.h). For
// two independent uniform directions the cosine between them is uniform on [-1, 1]; a
// Kolmogorov-Smirnov test of the cosines between consecutive processed directions checks it (for
// importance-sampled directions, against independent pairs of the same sequence).
#include "bundle/DirectionSampler.h"
#include "modes/atlas/DirectionOrder.h"
#include "sampling/EnvironmentLight.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <set>
#include <shared/Random.h>
#include <vector>

using namespace bl;

namespace {

constexpr std::uint32_t kPairs = 8192;
constexpr std::uint32_t kStrata = 1024;
// KS critical values at alpha = 1e-3: 1.95 / sqrt(n) one-sample, 1.95 sqrt(2 / n) two-sample.
// The pairs overlap (each direction is in two) and each block is one point set, so the test is
// approximate; the orders it must reject sit beyond (Halton in its own order D = 0.52, in the
// blocks of 64 of the shuffle before 0.04; stratified in its order 0.93; DirectionOrder.h).
const double kCriticalOne = 1.95 / std::sqrt(double(kPairs));
const double kCriticalTwo = 1.95 * std::sqrt(2.0 / kPairs);

std::vector<double> consecutiveCosines(const DirectionSampler& s, const DirectionOrder& order) {
    std::vector<double> c;
    for (std::uint32_t i = 0; i < kPairs; ++i) c.push_back(glm::dot(s.sample(order(i)).omega, s.sample(order(i + 1)).omega));
    std::sort(c.begin(), c.end());
    return c;
}

double ksUniform(const std::vector<double>& sorted) {
    double d = 0.0;
    const double n = double(sorted.size());
    for (std::size_t k = 0; k < sorted.size(); ++k) {
        const double f = 0.5 * (sorted[k] + 1.0);
        d = std::max({d, std::abs(f - k / n), std::abs(f - (k + 1) / n)});
    }
    return d;
}

double ksTwoSample(const std::vector<double>& a, const std::vector<double>& b) {
    double d = 0.0;
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        const double x = std::min(a[i], b[j]);
        while (i < a.size() && a[i] <= x) ++i;
        while (j < b.size() && b[j] <= x) ++j;
        d = std::max(d, std::abs(double(i) / a.size() - double(j) / b.size()));
    }
    return d;
}

// A sky with one bright patch, so that importance-sampled directions cluster.
Environment patchySky() {
    Environment env;
    env.present = true;
    env.map = Image(32, 16);
    for (int y = 0; y < 16; ++y) {
        for (int x = 0; x < 32; ++x) {
            env.map.pixels()[std::size_t(y) * 32 + x] = glm::vec3(x >= 8 && x < 12 && y >= 3 && y < 6 ? 50.0f : 0.5f);
        }
    }
    return env;
}

} // namespace

TEST(DirectionOrder, ConsecutiveUniformDirectionsAreIndependent) {
    for (DirectionSequence seq : {DirectionSequence::Halton, DirectionSequence::Random, DirectionSequence::Stratified}) {
        for (std::uint32_t seed : {0u, 7u}) {
            const DirectionSampler sampler(seq, seed, kStrata);
            const double d = ksUniform(consecutiveCosines(sampler, DirectionOrder(seq, kStrata, seed)));
            EXPECT_LT(d, kCriticalOne) << "sequence " << int(seq) << " seed " << seed;
        }
    }
}

TEST(DirectionOrder, ConsecutiveImportanceDirectionsAreIndependent) {
    const Environment env = patchySky();
    const EnvironmentLight light(env, true);
    const DirectionSampler sampler(DirectionSequence::Importance, 3u, kStrata, &light, 0.1f);
    const std::vector<double> consecutive =
        consecutiveCosines(sampler, DirectionOrder(DirectionSequence::Importance, kStrata, 3u));
    // Reference: two directions of the same sequence at independent random indices.
    std::vector<double> independent;
    for (std::uint32_t i = 0; i < kPairs; ++i) {
        const auto a = std::uint32_t(shader::blHashRandom(11u, i) * float(4 * kPairs));
        const auto b = std::uint32_t(shader::blHashRandom(12u, i) * float(4 * kPairs));
        independent.push_back(glm::dot(sampler.sample(a).omega, sampler.sample(b).omega));
    }
    std::sort(independent.begin(), independent.end());
    EXPECT_LT(ksTwoSample(consecutive, independent), kCriticalTwo);
}

TEST(DirectionOrder, EveryFullBlockIsTheSequencesOwnPointSet) {
    // The shuffle only reorders: each block of B processed indices is the block of B sample indices,
    // so the stratification of a full Halton block or stratified pass is kept.
    for (DirectionSequence seq : {DirectionSequence::Halton, DirectionSequence::Stratified}) {
        const DirectionOrder order(seq, kStrata, 5u);
        const std::uint32_t b = order.block();
        EXPECT_EQ(b, 1024u); // the stratified pass of kStrata cells, Halton's block
        for (std::uint32_t block = 0; block < 3; ++block) {
            std::set<std::uint32_t> seen;
            for (std::uint32_t i = block * b; i < (block + 1) * b; ++i) seen.insert(order(i));
            EXPECT_EQ(seen.size(), b);
            EXPECT_EQ(*seen.begin(), block * b);
            EXPECT_EQ(*seen.rbegin(), (block + 1) * b - 1);
        }
    }
    // Any block size, e.g. a stratified pass of 31^2 cells (strata 1000).
    EXPECT_EQ(DirectionOrder(DirectionSequence::Stratified, 1000, 1u).block(), 961u);
    std::set<std::uint32_t> seen;
    for (std::uint32_t i = 0; i < 961; ++i) seen.insert(permuteIndex(i, 961, 0x1234u));
    EXPECT_EQ(seen.size(), 961u);
    EXPECT_EQ(*seen.rbegin(), 960u);
}
