// Small helpers for recording commands: synchronization2 barriers.
#pragma once

#include <cstdint>
#include <vulkan/vulkan.h>

namespace bl::vk {

struct ImageTransition {
    VkImageLayout oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImageLayout newLayout = VK_IMAGE_LAYOUT_GENERAL;
    VkPipelineStageFlags2 srcStage = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkAccessFlags2 srcAccess = VK_ACCESS_2_MEMORY_WRITE_BIT;
    VkPipelineStageFlags2 dstStage = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkAccessFlags2 dstAccess = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    std::uint32_t baseLayer = 0;
    std::uint32_t layerCount = VK_REMAINING_ARRAY_LAYERS;
};

void transitionImage(VkCommandBuffer cmd, VkImage image, const ImageTransition& t);

// Makes all earlier writes of `srcStage` visible to `dstStage` (global memory barrier).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkPipelineStageFlags2 dstStage);

} // namespace bl::vk
