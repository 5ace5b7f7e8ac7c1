#include "vk/BoundSet.h"

#include "base/Error.h"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

namespace bl::vk {

Bound Bound::storageBuffer(std::uint32_t binding, VkBuffer buffer) {
    return {binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, buffer};
}

Bound Bound::uniformBuffer(std::uint32_t binding, VkBuffer buffer) {
    return {binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, buffer};
}

Bound Bound::storageImage(std::uint32_t binding, VkImageView view) {
    return {binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_NULL_HANDLE, view, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL};
}

Bound Bound::sampledImage(std::uint32_t binding, VkImageView view, VkSampler sampler) {
    return {binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, view, sampler,
            VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
}

Bound Bound::storageImages(std::uint32_t binding, std::span<const VkImageView> views) {
    Bound b = storageImage(binding, views.empty() ? VK_NULL_HANDLE : views.front());
    b.array.assign(views.begin(), views.end());
    return b;
}

Bound Bound::visibleTo(VkShaderStageFlags shaderStages) && {
    stages = shaderStages;
    return std::move(*this);
}

BoundSet::BoundSet(VkDevice device, std::initializer_list<Bound> bindings, VkShaderStageFlags stages)
    : mDevice(device), mBindings(bindings) {
    std::vector<Binding> layout;
    std::map<VkDescriptorType, std::uint32_t> perType;
    for (const Bound& b : mBindings) {
        const bool missing = b.holdsBuffer() ? b.buffer == VK_NULL_HANDLE
                                             : b.view == VK_NULL_HANDLE ||
                                                   std::find(b.array.begin(), b.array.end(), VK_NULL_HANDLE) != b.array.end();
        if (missing) {
            throw Error("descriptor set: binding " + std::to_string(b.binding) + " is given no resource");
        }
        if (std::count_if(mBindings.begin(), mBindings.end(), [&](const Bound& o) { return o.binding == b.binding; }) > 1) {
            throw Error("descriptor set: binding " + std::to_string(b.binding) + " is listed twice");
        }
        layout.push_back({b.binding, b.type, b.stages != 0 ? b.stages : stages, b.count()});
        perType[b.type] += b.count();
    }
    mLayout = makeDescriptorSetLayout(device, layout);
    std::uint32_t most = 1;
    for (const auto& [type, count] : perType) most = std::max(most, count);
    mPool = DescriptorPool(device, 1, most);
    mSet = mPool.allocate(mLayout.get());
    write(mBindings);
}

BoundSet::BoundSet(BoundSet&& other) noexcept
    : mDevice(other.mDevice), mBindings(std::move(other.mBindings)), mLayout(std::move(other.mLayout)),
      mPool(std::move(other.mPool)), mSet(std::exchange(other.mSet, VK_NULL_HANDLE)) {}

BoundSet& BoundSet::operator=(BoundSet&& other) noexcept {
    if (this != &other) {
        mDevice = other.mDevice;
        mBindings = std::move(other.mBindings);
        mLayout = std::move(other.mLayout);
        mPool = std::move(other.mPool);
        mSet = std::exchange(other.mSet, VK_NULL_HANDLE);
    }
    return *this;
}

Bound& BoundSet::entry(std::uint32_t binding) {
    for (Bound& b : mBindings) {
        if (b.binding == binding) return b;
    }
    throw Error("descriptor set: binding " + std::to_string(binding) + " is not one of the set's");
}

void BoundSet::rebind(std::uint32_t binding, VkBuffer buffer) {
    Bound& b = entry(binding);
    if (!b.holdsBuffer() || buffer == VK_NULL_HANDLE) {
        throw Error("descriptor set: binding " + std::to_string(binding) +
                    (b.holdsBuffer() ? " is given no buffer" : " holds an image, not a buffer"));
    }
    b.buffer = buffer;
    write({b});
}

void BoundSet::rebind(std::uint32_t binding, VkImageView view) {
    Bound& b = entry(binding);
    if (b.holdsBuffer() || !b.array.empty() || view == VK_NULL_HANDLE) {
        throw Error("descriptor set: binding " + std::to_string(binding) +
                    (b.holdsBuffer() ? " holds a buffer, not an image"
                     : !b.array.empty() ? " is an array: rebind() takes one image"
                                        : " is given no image"));
    }
    b.view = view;
    write({b});
}

void BoundSet::write(const std::vector<Bound>& bindings) const {
    DescriptorWriter writer;
    for (const Bound& b : bindings) {
        if (b.holdsBuffer()) {
            writer.buffer(b.binding, b.type, b.buffer);
        } else if (b.array.empty()) {
            writer.image(b.binding, b.type, b.view, b.imageLayout, b.sampler);
        } else {
            for (std::uint32_t i = 0; i < b.count(); ++i) {
                writer.image(b.binding, b.type, b.array[i], b.imageLayout, b.sampler, i);
            }
        }
    }
    writer.update(mDevice, mSet);
}

} // namespace bl::vk
