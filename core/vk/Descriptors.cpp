#include "vk/Descriptors.h"

#include "base/Error.h"
#include "vk/Check.h"

#include <mutex>
#include <string>
#include <utility>

namespace bl::vk {

namespace {
using TypeCounts = std::map<VkDescriptorType, std::uint32_t>;

// Each layout's descriptor counts by type, for the pools' own accounting (a layout handle does not
// tell them), keyed by device and handle (handle values are unique per device only). A destroyed
// layout's handle value may come back for a new layout, which overwrites it; entries are a few
// bytes and a process makes hundreds of layouts at most, so none is removed.
struct LayoutCounts {
    std::mutex mutex;
    std::map<std::pair<VkDevice, VkDescriptorSetLayout>, TypeCounts> counts;
};

LayoutCounts& layoutCounts() {
    static LayoutCounts registry;
    return registry;
}
} // namespace

DescriptorSetLayout makeDescriptorSetLayout(VkDevice device, std::span<const Binding> bindings) {
    std::vector<VkDescriptorSetLayoutBinding> list;
    for (const Binding& b : bindings) {
        list.push_back({b.binding, b.type, b.count, b.stages, nullptr});
    }
    VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    info.bindingCount = static_cast<std::uint32_t>(list.size());
    info.pBindings = list.data();
    VkDescriptorSetLayout raw = VK_NULL_HANDLE;
    BL_VK_CHECK(vkCreateDescriptorSetLayout(device, &info, nullptr, &raw));
    DescriptorSetLayout layout(device, raw); // owned before anything below may throw
    TypeCounts counts;
    for (const Binding& b : bindings) counts[b.type] += b.count;
    LayoutCounts& registry = layoutCounts();
    const std::lock_guard lock(registry.mutex);
    registry.counts[{device, raw}] = std::move(counts);
    return layout;
}

DescriptorPool::DescriptorPool(VkDevice device, std::uint32_t maxSets, std::uint32_t perType) {
    VkDescriptorPoolSize sizes[] = {
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, perType},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, perType},
        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, perType},
        {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, perType},
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, perType},
    };
    VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    info.maxSets = maxSets;
    info.poolSizeCount = static_cast<std::uint32_t>(std::size(sizes));
    info.pPoolSizes = sizes;
    VkDescriptorPool raw = VK_NULL_HANDLE;
    BL_VK_CHECK(vkCreateDescriptorPool(device, &info, nullptr, &raw));
    mPool = DescriptorPoolHandle(device, raw);
    mMaxSets = maxSets;
    mSetsLeft = maxSets;
    mPerType = perType;
    for (const VkDescriptorPoolSize& size : sizes) mLeft[size.type] = size.descriptorCount;
}

VkDescriptorSet DescriptorPool::allocate(VkDescriptorSetLayout layout) {
    if (mSetsLeft == 0) {
        throw Error("descriptor pool: all " + std::to_string(mMaxSets) + " sets handed out; size the pool for every set it holds");
    }
    TypeCounts needs;
    {
        LayoutCounts& registry = layoutCounts();
        const std::lock_guard lock(registry.mutex);
        const auto found = registry.counts.find({mPool.device(), layout});
        if (found == registry.counts.end()) {
            throw Error("descriptor pool: a set layout not made by makeDescriptorSetLayout, whose descriptors it "
                        "cannot count");
        }
        needs = found->second;
    }
    for (const auto& [type, count] : needs) {
        const std::uint32_t left = mLeft.count(type) ? mLeft.at(type) : 0;
        if (count > left) {
            throw Error("descriptor pool: a set needs " + std::to_string(count) + " descriptor(s) of type " +
                        std::to_string(int(type)) + ", the pool has " + std::to_string(left) + " left of " +
                        std::to_string(mLeft.count(type) ? mPerType : 0) +
                        "; size the pool for every set it holds");
        }
    }
    VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    info.descriptorPool = mPool.get();
    info.descriptorSetCount = 1;
    info.pSetLayouts = &layout;
    VkDescriptorSet set = VK_NULL_HANDLE;
    BL_VK_CHECK(vkAllocateDescriptorSets(mPool.device(), &info, &set));
    --mSetsLeft;
    for (const auto& [type, count] : needs) mLeft[type] -= count;
    return set;
}

DescriptorWriter& DescriptorWriter::buffer(std::uint32_t binding, VkDescriptorType type, VkBuffer buffer,
                                           VkDeviceSize offset, VkDeviceSize range) {
    mBuffers.push_back({buffer, offset, range});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = type;
    w.pBufferInfo = &mBuffers.back();
    mWrites.push_back(w);
    return *this;
}

DescriptorWriter& DescriptorWriter::image(std::uint32_t binding, VkDescriptorType type, VkImageView view,
                                          VkImageLayout layout, VkSampler sampler, std::uint32_t arrayElement) {
    mImages.push_back({sampler, view, layout});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = binding;
    w.dstArrayElement = arrayElement;
    w.descriptorCount = 1;
    w.descriptorType = type;
    w.pImageInfo = &mImages.back();
    mWrites.push_back(w);
    return *this;
}

void DescriptorWriter::update(VkDevice device, VkDescriptorSet set) {
    for (VkWriteDescriptorSet& w : mWrites) {
        w.dstSet = set;
    }
    vkUpdateDescriptorSets(device, static_cast<std::uint32_t>(mWrites.size()), mWrites.data(), 0, nullptr);
}

} // namespace bl::vk
