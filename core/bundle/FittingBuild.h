// The fitting bundle build every bundle mode runs: submit the builds of a pool's bundles, read the
// pool's overflow counter, and where they did not fit grow the pool to what they asked for and
// build again; where the memory limits cannot hold them, refuse with one message that names how
// many bundles (or what resolution) would fit. A build that overflowed left its lists incomplete,
// so nothing of it may be used: the passes after the build check the counter too (the pool
// contract, BundlePool.h), and the mode's iteration continues only after this returns.
#pragma once

#include "bundle/BundlePool.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace bl {

// What is being built, for the refusal: `mode` bundles of `resolution`^2 pixels each.
struct FittingBuildRequest {
    std::string mode;
    std::uint32_t bundles = 1;
    std::uint32_t resolution = 0;
};

// Runs `submit` (one submission that resets the pool and records every build, and waits for it)
// until the builds fit; returns the nodes they used. Each rebuild adds one to `rebuilds`.
std::uint64_t buildFitting(BundlePool& pool, const FittingBuildRequest& request, const std::function<void()>& submit,
                           std::uint64_t& rebuilds);

// The next iteration's builds recorded at the end of this iteration's submission, where their
// frames depend on the iteration's index and seed only (atlas, multibounce): one submission and
// wait per iteration instead of a build submission and a use submission. After the wait, check()
// notes whether they fit. The next iteration take()s them: held if they fit; if they overflowed,
// the pool grows then (a rebuild, counted where it is used: a last, unused prefetch costs nothing)
// and that iteration builds on its own with buildFitting (which refuses what the limits cannot hold).
struct PrefetchKey {
    std::uint32_t iteration = 0;
    std::uint64_t seed = 0;
    double time = 0.0;
    bool operator==(const PrefetchKey&) const = default;
};

class PrefetchedBuild {
public:
    // After the wait of the submission that recorded the builds of `next`.
    void check(const BundlePool& pool, const PrefetchKey& next);
    // Before iteration `key` uses its bundles: true if the pool holds them (their nodes into
    // `nodesLast`); false if it must build them now, after growing the pool (one more in
    // `rebuilds`) where they were prefetched and overflowed.
    bool take(BundlePool& pool, const PrefetchKey& key, std::uint64_t& nodesLast, std::uint64_t& rebuilds);

private:
    std::optional<PrefetchKey> mKey;
    BundlePoolStatus mStatus;
};

// The refusal's text for builds that asked for `requested` nodes of a pool that holds at most
// `maxNodes` of `bytesPerNode` bytes (exposed for its test).
std::string fittingBuildRefusal(const FittingBuildRequest& request, std::uint64_t requested, std::uint64_t maxNodes,
                                std::uint64_t bytesPerNode);

} // namespace bl
