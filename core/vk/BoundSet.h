// One descriptor set whose bindings are listed once. Each entry names its binding number, its
// descriptor type and the resource it holds; from that one list the set makes its layout, a pool
// sized for exactly that set, the set and its writes. A layout and its writes can then not disagree
// (a binding added to one list and forgotten in the other), and a pass's set-up lists each
// resource once instead of three times (layout, pool size, writer).
#pragma once

#include "vk/Descriptors.h"
#include "vk/Handle.h"

#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

namespace bl::vk {

// One binding and the resource it holds.
struct Bound {
    std::uint32_t binding = 0;
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
    VkImageLayout imageLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    std::vector<VkImageView> array; // an array binding of storage images: element i is array[i]
    VkShaderStageFlags stages = 0;  // 0: the stages the set gives every binding

    static Bound storageBuffer(std::uint32_t binding, VkBuffer buffer);
    static Bound uniformBuffer(std::uint32_t binding, VkBuffer buffer);
    // A storage image is read and written in VK_IMAGE_LAYOUT_GENERAL.
    static Bound storageImage(std::uint32_t binding, VkImageView view);
    // A combined image sampler read in VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL.
    static Bound sampledImage(std::uint32_t binding, VkImageView view, VkSampler sampler);
    // An array of storage images (GENERAL layout), one element per view.
    static Bound storageImages(std::uint32_t binding, std::span<const VkImageView> views);
    // This binding visible to `shaderStages` instead of the set's stages.
    Bound visibleTo(VkShaderStageFlags shaderStages) &&;
    std::uint32_t count() const { return array.empty() ? 1u : static_cast<std::uint32_t>(array.size()); }

    // A storage or uniform buffer (else an image).
    bool holdsBuffer() const {
        return type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER || type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    }
};

class BoundSet {
public:
    BoundSet() = default;
    // `stages`: the shader stages every binding is visible to.
    BoundSet(VkDevice device, std::initializer_list<Bound> bindings,
             VkShaderStageFlags stages = VK_SHADER_STAGE_COMPUTE_BIT);
    BoundSet(BoundSet&& other) noexcept;
    BoundSet& operator=(BoundSet&& other) noexcept;
    BoundSet(const BoundSet&) = delete;
    BoundSet& operator=(const BoundSet&) = delete;

    explicit operator bool() const { return mSet != VK_NULL_HANDLE; }
    VkDescriptorSetLayout layout() const { return mLayout.get(); }
    VkDescriptorSet set() const { return mSet; }
    // The set alone, as a pass that binds only it takes it (vk::ComputePass::dispatch).
    std::span<const VkDescriptorSet> sets() const { return {&mSet, 1}; }

    // Points a listed binding at another resource of the same kind (a buffer that grew, an image
    // made again); throws for a binding the set does not list, a resource of the other kind (a
    // buffer for an image binding or the reverse) and a null handle.
    void rebind(std::uint32_t binding, VkBuffer buffer);
    void rebind(std::uint32_t binding, VkImageView view);

private:
    Bound& entry(std::uint32_t binding);
    void write(const std::vector<Bound>& bindings) const;

    VkDevice mDevice = VK_NULL_HANDLE;
    std::vector<Bound> mBindings;
    DescriptorSetLayout mLayout;
    DescriptorPool mPool;
    VkDescriptorSet mSet = VK_NULL_HANDLE;
};

} // namespace bl::vk
