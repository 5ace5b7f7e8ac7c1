// Small helpers for recording commands: synchronization2 barriers.
#pragma once

#include <cstdint>
#include <vector>
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

// The transitions every raster pass makes: from anything (contents discarded) to a colour or
// depth attachment, and from a written colour attachment to GENERAL for compute-shader reads.
ImageTransition toColorAttachment();
ImageTransition toDepthAttachment();
ImageTransition colorAttachmentToGeneral();

// Dynamic rendering into colour attachments (all cleared to `clearColor`) and an optional depth
// attachment (cleared to `clearDepth`, not stored), with the scissor covering `extent` and the
// viewport covering `extent`, or `viewport` when its width is not zero.
struct RenderTargets {
    std::vector<VkImageView> colors;
    VkClearColorValue clearColor{};
    VkImageView depth = VK_NULL_HANDLE;
    float clearDepth = 0.0f; // reversed depth: 0 is infinitely far
    VkExtent2D extent{};
    VkViewport viewport{}; // beyond `extent`: the part outside is scissored away
};
void beginRendering(VkCommandBuffer cmd, const RenderTargets& targets);

// Makes all earlier writes of `srcStage` visible to `dstStage` (global memory barrier).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkPipelineStageFlags2 dstStage);
// The end of a frame's compute work: its writes visible to the host and to the read-back copies.
inline void computeToHost(VkCommandBuffer cmd) {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_HOST_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT);
}

} // namespace bl::vk
