// Shader modules and pipelines. Graphics pipelines use dynamic rendering (core in Vulkan 1.3), so
// there are no render pass or framebuffer objects; viewport and scissor are dynamic state.
#pragma once

#include "vk/Handle.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace bl::vk {

ShaderModule makeShaderModule(VkDevice device, std::span<const std::uint32_t> spirv);

PipelineLayout makePipelineLayout(VkDevice device, std::span<const VkDescriptorSetLayout> sets,
                                  std::uint32_t pushConstantBytes, VkShaderStageFlags pushStages);

struct GraphicsPipelineDesc {
    std::span<const std::uint32_t> vertexShader;
    std::span<const std::uint32_t> fragmentShader;
    std::vector<VkVertexInputBindingDescription> vertexBindings;
    std::vector<VkVertexInputAttributeDescription> vertexAttributes;
    std::vector<VkFormat> colorFormats;
    VkFormat depthFormat = VK_FORMAT_UNDEFINED;
    VkCompareOp depthCompare = VK_COMPARE_OP_GREATER; // reversed depth: larger is nearer
    bool depthWrite = true;
    VkCullModeFlags cullMode = VK_CULL_MODE_NONE; // surfaces are two-sided
    VkPipelineLayout layout = VK_NULL_HANDLE;
    // Specialization constants constant_id = 0, 1, ... of both stages (as makeComputePipeline's).
    std::vector<std::uint32_t> specialization;
};

Pipeline makeGraphicsPipeline(VkDevice device, const GraphicsPipelineDesc& desc);
// `specialization`: the values of the shader's specialization constants constant_id = 0, 1, ...
// (32 bits each), for settings fixed for the pipeline's life that gate whole code paths: the
// compiler drops the paths they rule out (on lavapipe, which runs both sides of every branch
// under a mask, that code would otherwise cost its full time).
Pipeline makeComputePipeline(VkDevice device, std::span<const std::uint32_t> spirv, VkPipelineLayout layout,
                             std::span<const std::uint32_t> specialization = {});

// Workgroups needed to cover `items` with groups of `groupSize`.
inline std::uint32_t groupCount(std::uint32_t items, std::uint32_t groupSize) {
    return (items + groupSize - 1) / groupSize;
}

// Workgroups of groupSize x groupSize covering a width x height image.
inline glm::uvec3 groupCount(std::uint32_t width, std::uint32_t height, std::uint32_t groupSize) {
    return {groupCount(width, groupSize), groupCount(height, groupSize), 1u};
}

} // namespace bl::vk
