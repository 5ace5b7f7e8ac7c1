#include "bundle/FittingBuild.h"

#include "base/Error.h"

#include <cmath>
#include <cstdio>

namespace bl {

namespace {

constexpr double kMiB = 1024.0 * 1024.0;

std::string mebibytes(double bytes) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.1f MiB", bytes / kMiB);
    return text;
}

} // namespace

std::string fittingBuildRefusal(const FittingBuildRequest& request, std::uint64_t requested, std::uint64_t maxNodes,
                                std::uint64_t bytesPerNode) {
    const std::string side = std::to_string(request.resolution);
    std::string text = request.mode + ": " + std::to_string(request.bundles) + (request.bundles == 1 ? " bundle" : " bundles") +
                       " of " + side + "^2 pixels " + (request.bundles == 1 ? "needs " : "need ") + std::to_string(requested) + " nodes (" +
                       mebibytes(double(requested) * double(bytesPerNode)) + "), the pool holds at most " +
                       std::to_string(maxNodes) + " (" + mebibytes(double(maxNodes) * double(bytesPerNode)) +
                       ": memory_cap_mib or the device's limits); ";
    // The nodes a build needs grow with its bundles and with the pixels of each (depth complexity
    // aside): what fits scales with maxNodes / requested.
    const double share = double(maxNodes) / double(requested);
    const auto fit = static_cast<std::uint64_t>(double(request.bundles) * share);
    const auto resolution = static_cast<std::uint64_t>(double(request.resolution) * std::sqrt(share));
    if (request.bundles > 1 && fit >= 1) {
        return text + "about " + std::to_string(fit) + " bundles fit at this resolution, or all " +
               std::to_string(request.bundles) + " at bundle_resolution of about " + std::to_string(resolution);
    }
    return text + "lower bundle_resolution (about " + std::to_string(resolution) + " would fit)";
}

std::uint64_t buildFitting(BundlePool& pool, const FittingBuildRequest& request, const std::function<void()>& submit,
                           std::uint64_t& rebuilds) {
    for (;;) {
        submit();
        const BundlePoolStatus status = pool.status();
        if (!status.overflowed()) {
            return status.requested;
        }
        if (!pool.grow(status)) {
            throw Error(fittingBuildRefusal(request, status.requested, pool.maxNodes(), pool.bytesPerNode()));
        }
        ++rebuilds;
    }
}

void PrefetchedBuild::check(const BundlePool& pool, const PrefetchKey& next) {
    mKey = next;
    mStatus = pool.status();
}

bool PrefetchedBuild::take(BundlePool& pool, const PrefetchKey& key, std::uint64_t& nodesLast, std::uint64_t& rebuilds) {
    if (!mKey || !(*mKey == key)) {
        return false;
    }
    mKey.reset();
    if (!mStatus.overflowed()) {
        nodesLast = mStatus.requested;
        return true;
    }
    // Where the pool cannot grow, buildFitting's own overflow says why.
    if (pool.grow(mStatus)) {
        ++rebuilds;
    }
    return false;
}

} // namespace bl
