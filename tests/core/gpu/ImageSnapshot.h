// Test helper: copies layer 0 of an image, in VK_IMAGE_LAYOUT_GENERAL, to another inside a command
// buffer, so a test can keep what one pass wrote before a second pass in the same command buffer
// overwrites it.
#pragma once

#include "vk/Commands.h"
#include "vk/GpuImage.h"

namespace bl::test {

inline void recordSnapshot(VkCommandBuffer cmd, const vk::GpuImage& source, const vk::GpuImage& snapshot) {
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT);
    VkImageCopy region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstSubresource = region.srcSubresource;
    region.extent = {source.desc().width, source.desc().height, 1};
    vkCmdCopyImage(cmd, source.get(), VK_IMAGE_LAYOUT_GENERAL, snapshot.get(), VK_IMAGE_LAYOUT_GENERAL, 1, &region);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
}

// A blank image shaped like `like`, for recordSnapshot (move it to GENERAL before the copy).
inline vk::GpuImage makeSnapshotImage(const vk::Context& ctx, const vk::GpuImage& like) {
    return vk::GpuImage(ctx, {like.desc().width, like.desc().height, 1, like.desc().format, VK_IMAGE_USAGE_STORAGE_BIT});
}

} // namespace bl::test
