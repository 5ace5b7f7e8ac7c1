#include "vk/GpuTimer.h"

#include "base/Error.h"
#include "vk/Check.h"

#include <algorithm>

namespace bl::vk {

GpuTimer::GpuTimer(const Context& ctx, std::uint32_t maxScopes)
    : mDevice(ctx.device()), mPeriodNs(ctx.limits().timestampPeriod), mMaxScopes(maxScopes) {
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2 * maxScopes;
    VkQueryPool raw = VK_NULL_HANDLE;
    BL_VK_CHECK(vkCreateQueryPool(mDevice, &info, nullptr, &raw));
    mPool = QueryPool(mDevice, raw);
}

void GpuTimer::begin(VkCommandBuffer cmd) {
    vkCmdResetQueryPool(cmd, mPool.get(), 0, 2 * mMaxScopes);
    mScopeNames.clear();
}

std::uint32_t GpuTimer::start(VkCommandBuffer cmd, const std::string& name) {
    if (mScopeNames.size() >= mMaxScopes) {
        throw Error("GpuTimer: more than " + std::to_string(mMaxScopes) + " passes in one submission");
    }
    auto scope = static_cast<std::uint32_t>(mScopeNames.size());
    mScopeNames.push_back(name);
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, mPool.get(), 2 * scope);
    // lavapipe (Mesa 22.3) queues a timestamp with the pending rendering work and writes it at the
    // next flush, while it runs a compute dispatch at once: a compute-only pass timed without a
    // flush in between read ~0 (walking 0.5 M nodes in 1024^2 lists: 0.02 ms; 80 ms with it).
    // A pipeline barrier flushes there; elsewhere it is an execution dependency that keeps earlier
    // passes out of this pass's time.
    VkMemoryBarrier2 after{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    after.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    after.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &after;
    vkCmdPipelineBarrier2(cmd, &dependency);
    return scope;
}

void GpuTimer::stop(VkCommandBuffer cmd, std::uint32_t scope) {
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, mPool.get(), 2 * scope + 1);
}

void GpuTimer::collect() {
    if (mScopeNames.empty()) {
        return;
    }
    std::vector<std::uint64_t> stamps(2 * mScopeNames.size());
    BL_VK_CHECK(vkGetQueryPoolResults(mDevice, mPool.get(), 0, static_cast<std::uint32_t>(stamps.size()),
                                      stamps.size() * sizeof(std::uint64_t), stamps.data(),
                                      sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    for (std::size_t i = 0; i < mScopeNames.size(); ++i) {
        double ms = static_cast<double>(stamps[2 * i + 1] - stamps[2 * i]) * mPeriodNs * 1e-6;
        auto it = std::find_if(mTotals.begin(), mTotals.end(),
                               [&](const PassTime& p) { return p.name == mScopeNames[i]; });
        if (it == mTotals.end()) {
            mTotals.push_back({mScopeNames[i], 0.0, 0});
            it = mTotals.end() - 1;
        }
        it->totalMs += std::max(ms, 0.0);
        it->count += 1;
    }
    mScopeNames.clear();
}

} // namespace bl::vk
