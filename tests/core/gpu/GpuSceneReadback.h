// Reads a GpuScene buffer back to the host in tests (GpuScene hands out VkBuffers, not vk::Buffers).
#pragma once

#include "vk/Buffer.h"
#include "vk/Commands.h"

#include <vector>

namespace bl::test {

template <typename T> std::vector<T> readBack(const vk::Context& ctx, VkBuffer buffer, std::size_t count) {
    std::vector<T> items(count);
    const VkDeviceSize bytes = count * sizeof(T);
    vk::Buffer readback(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        const VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, buffer, readback.get(), 1, &region);
        // The fence alone does not make device writes visible to host reads.
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_HOST_BIT);
    });
    readback.download(ctx, items.data(), bytes);
    return items;
}

} // namespace bl::test
