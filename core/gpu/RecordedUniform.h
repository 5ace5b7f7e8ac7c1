// A uniform buffer whose contents are written inside the command buffer (vkCmdUpdateBuffer), not
// by the host. A pass recorded twice into one command buffer then reads, each time, the value
// recorded just before it; a host write (memcpy into mapped memory) would be seen by every record
// of that submission as the last value written (defect 6 of issue 10).
#pragma once

#include "vk/Buffer.h"
#include "vk/Commands.h"

namespace bl::gpu {

template <typename T> class RecordedUniform {
    // vkCmdUpdateBuffer's limits: at most 65536 bytes, a multiple of 4.
    static constexpr VkDeviceSize kMaxInlineUpdateBytes = 65536;
    static_assert(sizeof(T) % 4 == 0 && sizeof(T) <= kMaxInlineUpdateBytes, "vkCmdUpdateBuffer limits");

public:
    RecordedUniform() = default;
    explicit RecordedUniform(const vk::Context& ctx)
        : mBuffer(ctx, sizeof(T), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUse::Device) {}

    // Records the write of `value`, outside any rendering scope. The first barrier lets earlier
    // readers of the old value finish (write after read); the second makes the new value visible
    // to every later stage.
    void record(VkCommandBuffer cmd, const T& value) const {
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT);
        vkCmdUpdateBuffer(cmd, mBuffer.get(), 0, sizeof(T), &value);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    }

    VkBuffer get() const { return mBuffer.get(); }

private:
    vk::Buffer mBuffer;
};

} // namespace bl::gpu
