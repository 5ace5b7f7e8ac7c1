// One compute shader and what recording it needs: its pipeline layout (descriptor-set layouts and a
// push-constant block of type Push), its pipeline (with specialization constants), and the
// bind / bind sets / push / dispatch sequence every compute pass repeats. A mode's set-up then reads
// as a list of passes, and a push block of the wrong type does not compile.
#pragma once

#include "vk/Handle.h"
#include "vk/Pipeline.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <initializer_list>
#include <span>
#include <type_traits>

namespace bl::vk {

// For a shader without push constants.
struct NoPush {};

// The untyped part (ComputePass.cpp).
class ComputePipeline {
public:
    ComputePipeline() = default;
    ComputePipeline(VkDevice device, std::span<const std::uint32_t> spirv, std::uint32_t pushBytes,
                    std::initializer_list<VkDescriptorSetLayout> sets, std::span<const std::uint32_t> specialization);

    explicit operator bool() const { return mPipeline.get() != VK_NULL_HANDLE; }
    VkPipelineLayout layout() const { return mLayout.get(); }
    VkPipeline pipeline() const { return mPipeline.get(); }

protected:
    // Binds the pipeline and `sets` as sets 0, 1, ...; pushes `bytes` (none when pushBytes is 0).
    // Sets given must be all of the layout's (none: those bound before stay, for shaders that read
    // no descriptor); a different count is a programming error and throws.
    void bind(VkCommandBuffer cmd, std::span<const VkDescriptorSet> sets, const void* bytes) const;

private:
    vk::PipelineLayout mLayout;
    vk::Pipeline mPipeline;
    std::uint32_t mPushBytes = 0;
    std::uint32_t mSetCount = 0;
};

template <typename Push>
class ComputePass : public ComputePipeline {
    static_assert(std::is_trivially_copyable_v<Push>, "push constants are copied as bytes");

public:
    ComputePass() = default;
    // `sets`: the descriptor-set layouts, set 0 first. `specialization`: constant_id 0, 1, ... (32
    // bits each), for settings fixed for the pipeline's life (vk::makeComputePipeline).
    ComputePass(VkDevice device, std::span<const std::uint32_t> spirv,
                std::initializer_list<VkDescriptorSetLayout> sets = {},
                std::span<const std::uint32_t> specialization = {})
        : ComputePipeline(device, spirv, std::is_empty_v<Push> ? 0u : std::uint32_t(sizeof(Push)), sets,
                          specialization) {}

    // Binds, pushes `push` and dispatches `groups` workgroups.
    void dispatch(VkCommandBuffer cmd, const Push& push, glm::uvec3 groups,
                  std::span<const VkDescriptorSet> sets = {}) const {
        bind(cmd, sets, &push);
        vkCmdDispatch(cmd, groups.x, groups.y, groups.z);
    }
    void dispatch(VkCommandBuffer cmd, const Push& push, std::uint32_t groups,
                  std::span<const VkDescriptorSet> sets = {}) const {
        dispatch(cmd, push, glm::uvec3(groups, 1u, 1u), sets);
    }
    // The workgroup count read from `buffer` at `offset` (VkDispatchIndirectCommand).
    void dispatchIndirect(VkCommandBuffer cmd, const Push& push, VkBuffer buffer, VkDeviceSize offset,
                          std::span<const VkDescriptorSet> sets = {}) const {
        bind(cmd, sets, &push);
        vkCmdDispatchIndirect(cmd, buffer, offset);
    }
};

} // namespace bl::vk
