#include "vk/Pipeline.h"

#include "vk/Check.h"

namespace bl::vk {

namespace {
// The specialization of constants constant_id = 0, 1, ... to `values` (32 bits each); `entries`
// holds the map the result points to.
VkSpecializationInfo specializationInfo(std::span<const std::uint32_t> values,
                                        std::vector<VkSpecializationMapEntry>& entries) {
    entries.resize(values.size());
    for (std::uint32_t i = 0; i < entries.size(); ++i) {
        entries[i] = {i, static_cast<std::uint32_t>(i * sizeof(std::uint32_t)), sizeof(std::uint32_t)};
    }
    return {static_cast<std::uint32_t>(entries.size()), entries.data(), values.size_bytes(), values.data()};
}
} // namespace

ShaderModule makeShaderModule(VkDevice device, std::span<const std::uint32_t> spirv) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = spirv.size_bytes();
    info.pCode = spirv.data();
    VkShaderModule raw = VK_NULL_HANDLE;
    BL_VK_CHECK(vkCreateShaderModule(device, &info, nullptr, &raw));
    return ShaderModule(device, raw);
}

PipelineLayout makePipelineLayout(VkDevice device, std::span<const VkDescriptorSetLayout> sets,
                                  std::uint32_t pushConstantBytes, VkShaderStageFlags pushStages) {
    VkPushConstantRange range{pushStages, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = static_cast<std::uint32_t>(sets.size());
    info.pSetLayouts = sets.data();
    info.pushConstantRangeCount = pushConstantBytes ? 1 : 0;
    info.pPushConstantRanges = pushConstantBytes ? &range : nullptr;
    VkPipelineLayout raw = VK_NULL_HANDLE;
    BL_VK_CHECK(vkCreatePipelineLayout(device, &info, nullptr, &raw));
    return PipelineLayout(device, raw);
}

Pipeline makeGraphicsPipeline(VkDevice device, const GraphicsPipelineDesc& d) {
    ShaderModule vs = makeShaderModule(device, d.vertexShader);
    ShaderModule fs = makeShaderModule(device, d.fragmentShader);
    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vs.get();
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fs.get();
    stages[1].pName = "main";
    std::vector<VkSpecializationMapEntry> entries;
    const VkSpecializationInfo specialization = specializationInfo(d.specialization, entries);
    for (VkPipelineShaderStageCreateInfo& stage : stages) {
        stage.pSpecializationInfo = d.specialization.empty() ? nullptr : &specialization;
    }

    VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertexInput.vertexBindingDescriptionCount = static_cast<std::uint32_t>(d.vertexBindings.size());
    vertexInput.pVertexBindingDescriptions = d.vertexBindings.data();
    vertexInput.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(d.vertexAttributes.size());
    vertexInput.pVertexAttributeDescriptions = d.vertexAttributes.data();
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = d.cullMode;
    // World-space counter-clockwise is the front face (CONVENTIONS.md). Our projections put +up
    // at framebuffer row 0, so the image is upright and a triangle seen from its front keeps its
    // counter-clockwise order there (positive area in Vulkan's y-down formula).
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = d.depthFormat != VK_FORMAT_UNDEFINED;
    depth.depthWriteEnable = d.depthWrite && depth.depthTestEnable;
    depth.depthCompareOp = d.depthCompare;
    std::vector<VkPipelineColorBlendAttachmentState> blends(d.colorFormats.size());
    for (auto& b : blends) {
        b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                           VK_COLOR_COMPONENT_A_BIT;
    }
    VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend.attachmentCount = static_cast<std::uint32_t>(blends.size());
    blend.pAttachments = blends.data();
    VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamicStates;
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = static_cast<std::uint32_t>(d.colorFormats.size());
    rendering.pColorAttachmentFormats = d.colorFormats.data();
    rendering.depthAttachmentFormat = d.depthFormat;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = d.layout;
    VkPipeline raw = VK_NULL_HANDLE;
    BL_VK_CHECK(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &raw));
    return Pipeline(device, raw);
}

Pipeline makeComputePipeline(VkDevice device, std::span<const std::uint32_t> spirv, VkPipelineLayout layout,
                             std::span<const std::uint32_t> values) {
    ShaderModule module = makeShaderModule(device, spirv);
    std::vector<VkSpecializationMapEntry> entries;
    const VkSpecializationInfo specialization = specializationInfo(values, entries);
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module.get();
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = values.empty() ? nullptr : &specialization;
    info.layout = layout;
    VkPipeline raw = VK_NULL_HANDLE;
    BL_VK_CHECK(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &raw));
    return Pipeline(device, raw);
}

} // namespace bl::vk
