// GPU timestamps around named passes. Record start/stop into a command buffer, then collect()
// after it has completed; totals accumulate per name, so a mode can print ms per pass.
#pragma once

#include "base/PassTime.h"
#include "vk/Context.h"

#include <string>
#include <vector>

namespace bl::vk {

class GpuTimer {
public:
    GpuTimer() = default;
    GpuTimer(const Context& ctx, std::uint32_t maxScopes = 64);

    // Resets the queries; call once at the start of each command buffer that uses the timer.
    void begin(VkCommandBuffer cmd);
    std::uint32_t start(VkCommandBuffer cmd, const std::string& name);
    void stop(VkCommandBuffer cmd, std::uint32_t scope);
    // What `record` records, in a scope named `name`.
    template <typename Record> void timed(VkCommandBuffer cmd, const std::string& name, Record&& record) {
        const std::uint32_t scope = start(cmd, name);
        record();
        stop(cmd, scope);
    }
    // Reads the finished queries and adds them to the totals.
    void collect();

    const PassTimes& totals() const { return mTotals; }
    void clearTotals() { mTotals.clear(); }

private:
    VkDevice mDevice = VK_NULL_HANDLE;
    QueryPool mPool;
    double mPeriodNs = 1.0;
    std::uint32_t mMaxScopes = 0;
    std::vector<std::string> mScopeNames; // scopes recorded since begin()
    PassTimes mTotals;
};

} // namespace bl::vk
