// Move-only ownership of a Vulkan object created from a VkDevice: one alias per object kind, all
// sharing this one template so the move/destroy logic exists once.
#pragma once

#include <cstdint>
#include <utility>
#include <vulkan/vulkan.h>

namespace bl::vk {

template <typename T, auto Destroy> class DeviceHandle {
public:
    DeviceHandle() = default;
    DeviceHandle(VkDevice device, T handle) : mDevice(device), mHandle(handle) {}
    ~DeviceHandle() { reset(); }
    DeviceHandle(const DeviceHandle&) = delete;
    DeviceHandle& operator=(const DeviceHandle&) = delete;
    DeviceHandle(DeviceHandle&& other) noexcept
        : mDevice(other.mDevice), mHandle(std::exchange(other.mHandle, VK_NULL_HANDLE)) {}
    DeviceHandle& operator=(DeviceHandle&& other) noexcept {
        if (this != &other) {
            reset();
            mDevice = other.mDevice;
            mHandle = std::exchange(other.mHandle, VK_NULL_HANDLE);
        }
        return *this;
    }

    T get() const { return mHandle; }
    explicit operator bool() const { return mHandle != VK_NULL_HANDLE; }
    VkDevice device() const { return mDevice; }
    void reset() {
        if (mHandle != VK_NULL_HANDLE) {
            Destroy(mDevice, mHandle, nullptr);
            mHandle = VK_NULL_HANDLE;
        }
    }

private:
    VkDevice mDevice = VK_NULL_HANDLE;
    T mHandle = VK_NULL_HANDLE;
};

using BufferHandle = DeviceHandle<VkBuffer, vkDestroyBuffer>;
using ImageHandle = DeviceHandle<VkImage, vkDestroyImage>;
using ImageView = DeviceHandle<VkImageView, vkDestroyImageView>;
using Memory = DeviceHandle<VkDeviceMemory, vkFreeMemory>;
using Sampler = DeviceHandle<VkSampler, vkDestroySampler>;
using ShaderModule = DeviceHandle<VkShaderModule, vkDestroyShaderModule>;
using PipelineLayout = DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout>;
using Pipeline = DeviceHandle<VkPipeline, vkDestroyPipeline>;
using DescriptorSetLayout = DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using DescriptorPoolHandle = DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool>;
using CommandPool = DeviceHandle<VkCommandPool, vkDestroyCommandPool>;
using Fence = DeviceHandle<VkFence, vkDestroyFence>;
using QueryPool = DeviceHandle<VkQueryPool, vkDestroyQueryPool>;

} // namespace bl::vk
