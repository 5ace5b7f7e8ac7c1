#include "modes/atlas/DirectionOrder.h"

#include <algorithm>
#include <cmath>
#include <shared/Random.h>

namespace bl {

namespace {
constexpr std::uint32_t kHaltonBlock = 1024; // DirectionOrder.h: the measured independence
constexpr std::uint32_t kShuffleKey = 0x2545f491u; // keys the permutations apart from the sampler's own hashes
} // namespace

DirectionOrder::DirectionOrder(DirectionSequence sequence, std::uint32_t strata, std::uint32_t seed) : mSeed(seed) {
    // The stratified pass as DirectionSampler::unitSquare cycles it: side x side cells.
    const auto side = static_cast<std::uint32_t>(std::max(1.0, std::floor(std::sqrt(double(std::max(strata, 1u))))));
    mBlock = sequence == DirectionSequence::Stratified ? side * side : kHaltonBlock;
}

std::uint32_t DirectionOrder::operator()(std::uint32_t i) const {
    const std::uint32_t block = i / mBlock;
    const std::uint32_t key = shader::blHash(mSeed ^ kShuffleKey ^ shader::blHash(block + 0x68e31da4u));
    return block * mBlock + permuteIndex(i % mBlock, mBlock, key);
}

std::uint32_t permuteIndex(std::uint32_t i, std::uint32_t n, std::uint32_t key) {
    if (n <= 1) return 0;
    std::uint32_t w = n - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    do {
        i ^= key;
        i *= 0xe170893du;
        i ^= key >> 16;
        i ^= (i & w) >> 4;
        i ^= key >> 8;
        i *= 0x0929eb3fu;
        i ^= key >> 23;
        i ^= (i & w) >> 1;
        i *= 1u | key >> 27;
        i *= 0x6935fa69u;
        i ^= (i & w) >> 11;
        i *= 0x74dcb303u;
        i ^= (i & w) >> 2;
        i *= 0x9e501cc3u;
        i ^= (i & w) >> 2;
        i *= 0xc860a3dfu;
        i &= w;
        i ^= i >> 5;
    } while (i >= n);
    return (i + key) % n;
}

} // namespace bl
