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

// The refusal's text for builds that asked for `requested` nodes of a pool that holds at most
// `maxNodes` of `bytesPerNode` bytes (exposed for its test).
std::string fittingBuildRefusal(const FittingBuildRequest& request, std::uint64_t requested, std::uint64_t maxNodes,
                                std::uint64_t bytesPerNode);

} // namespace bl
