#include "vk/ComputePass.h"

#include "base/Error.h"

#include <string>
#include <vector>

namespace bl::vk {

ComputePipeline::ComputePipeline(VkDevice device, std::span<const std::uint32_t> spirv, std::uint32_t pushBytes,
                                 std::initializer_list<VkDescriptorSetLayout> sets,
                                 std::span<const std::uint32_t> specialization)
    : mPushBytes(pushBytes), mSetCount(static_cast<std::uint32_t>(sets.size())) {
    const std::vector<VkDescriptorSetLayout> layouts(sets);
    mLayout = makePipelineLayout(device, layouts, pushBytes, VK_SHADER_STAGE_COMPUTE_BIT);
    mPipeline = makeComputePipeline(device, spirv, mLayout.get(), specialization);
}

void ComputePipeline::bind(VkCommandBuffer cmd, std::span<const VkDescriptorSet> sets, const void* bytes) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mPipeline.get());
    if (!sets.empty()) {
        if (sets.size() != mSetCount) {
            throw Error("compute pass: " + std::to_string(sets.size()) + " descriptor sets bound to a layout of " +
                        std::to_string(mSetCount));
        }
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mLayout.get(), 0,
                                static_cast<std::uint32_t>(sets.size()), sets.data(), 0, nullptr);
    }
    if (mPushBytes > 0) {
        vkCmdPushConstants(cmd, mLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, mPushBytes, bytes);
    }
}

} // namespace bl::vk
