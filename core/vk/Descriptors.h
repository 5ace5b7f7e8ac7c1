// Descriptor set layouts, a pool that owns its sets, and a writer that batches updates.
#pragma once

#include "vk/Handle.h"

#include <deque>
#include <initializer_list>
#include <map>
#include <span>
#include <vector>

namespace bl::vk {

struct Binding {
    std::uint32_t binding;
    VkDescriptorType type;
    VkShaderStageFlags stages;
    std::uint32_t count = 1;
};

DescriptorSetLayout makeDescriptorSetLayout(VkDevice device, std::span<const Binding> bindings);
inline DescriptorSetLayout makeDescriptorSetLayout(VkDevice device, std::initializer_list<Binding> bindings) {
    return makeDescriptorSetLayout(device, std::span<const Binding>(bindings.begin(), bindings.size()));
}

class DescriptorPool {
public:
    DescriptorPool() = default;
    // Room for `maxSets` sets with up to `perType` descriptors of each common type.
    DescriptorPool(VkDevice device, std::uint32_t maxSets, std::uint32_t perType);
    // A set of `layout` (made by makeDescriptorSetLayout). The pool counts what it hands out and
    // throws when a set would overdraw it: Vulkan lets a driver allocate past a pool's sizes (lavapipe
    // does) or fail, so an undersized pool would otherwise fail only on some devices.
    VkDescriptorSet allocate(VkDescriptorSetLayout layout);

private:
    DescriptorPoolHandle mPool;
    std::uint32_t mMaxSets = 0;
    std::uint32_t mSetsLeft = 0;
    std::uint32_t mPerType = 0;
    std::map<VkDescriptorType, std::uint32_t> mLeft;
};

class DescriptorWriter {
public:
    DescriptorWriter& buffer(std::uint32_t binding, VkDescriptorType type, VkBuffer buffer,
                             VkDeviceSize offset = 0, VkDeviceSize range = VK_WHOLE_SIZE);
    DescriptorWriter& image(std::uint32_t binding, VkDescriptorType type, VkImageView view,
                            VkImageLayout layout, VkSampler sampler = VK_NULL_HANDLE,
                            std::uint32_t arrayElement = 0);
    void update(VkDevice device, VkDescriptorSet set);

private:
    std::deque<VkDescriptorBufferInfo> mBuffers; // deque: stable addresses for the writes
    std::deque<VkDescriptorImageInfo> mImages;
    std::vector<VkWriteDescriptorSet> mWrites;
};

} // namespace bl::vk
