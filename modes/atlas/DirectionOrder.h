// The order in which the atlas processes its global directions when the glossy transfer is on
// ([HHGM10 §5.4], papers/EQUATIONS.md). The transfer stores at direction i what a lobe
// reflects toward omega_{i+1}, and its estimate is unbiased only if omega_{i+1} is independent of
// omega_i. No sequence gives that in its own order: consecutive Halton points (bases 5 and 7, also
// under directions = importance) sit at nearly fixed offsets from each other (+30% on the glossy
// Cornell box's left wall, measured), consecutive stratified cells are neighbours in the same
// latitude band. So every sequence is taken in a random order within blocks: the i-th direction
// processed is sample index  block * B + pi_block(i mod B),  pi a keyed random permutation of
// [0, B). The next direction is then any other point of the block, and every full block is the
// same point set as in the sequence's own order (its stratification kept):
//   Halton, importance, random   B = 1024
//   stratified                   B = the pass, side^2 cells (DirectionSampler::unitSquare), so
//                                that the next cell is any cell of the sphere, not the neighbour
// Measured (KS distance of the cosine between consecutive directions from the independent pairs'
// uniform law, 8192 pairs, 3 seeds; 0.02 is alpha = 1e-3): Halton in its order 0.52, in blocks of
// 64 (the shuffle this replaces) 0.038-0.045, of 256 0.011-0.014, of 1024 0.008-0.010 (random
// directions 0.005-0.013); stratified in its order 0.93, in blocks of 64 or 256 0.38-0.44 (a block
// is a latitude band), of the whole pass 0.006-0.012. What remains is O(1/B): a direction is never
// followed by itself. A run shorter than B takes a random subset of the block, not its prefix.
#pragma once

#include "bundle/DirectionSampler.h"

#include <cstdint>

namespace bl {

class DirectionOrder {
public:
    DirectionOrder(DirectionSequence sequence, std::uint32_t strata, std::uint32_t seed);
    // The sampler index of the i-th direction processed.
    std::uint32_t operator()(std::uint32_t i) const;
    std::uint32_t block() const { return mBlock; }

private:
    std::uint32_t mBlock;
    std::uint32_t mSeed;
};

// A random permutation of [0, n) keyed by `key`, evaluated at i < n without storing it (Kensler,
// "Correlated Multi-Jittered Sampling", 2013: an invertible hash on the next power of two, walked
// until it lands below n).
std::uint32_t permuteIndex(std::uint32_t i, std::uint32_t n, std::uint32_t key);

} // namespace bl
