// The Vulkan context: instance (+ validation messenger), the chosen physical device, a logical
// device with one graphics+compute queue, and a command pool. Headless by default; a window
// (viewer/) adds the instance extensions of its surface and asks for the swapchain extension.
//
// Device choice (`--device`): an index into the list of Vulkan 1.3 devices, or a case-insensitive
// substring of the device name; by default the first discrete GPU, else integrated, else any other
// GPU, else the CPU implementation (lavapipe).
#pragma once

#include "vk/Handle.h"

#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace bl::vk {

struct ContextOptions {
    std::string device;      // "" = automatic
    bool validation = false; // VK_LAYER_KHRONOS_validation + messenger; errors are counted
    std::vector<std::string> instanceExtensions; // e.g. a window system's surface extensions
    bool swapchain = false;                      // enable VK_KHR_swapchain on the device
};

struct DeviceInfo {
    std::uint32_t index = 0;
    std::string name;
    std::string type; // "discrete GPU", "CPU", …
    std::string driverName;
    std::string driverInfo;
    std::string apiVersion; // "1.3.230"
    std::string describe() const;
};

class Context {
public:
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return mInstance; }
    VkPhysicalDevice physicalDevice() const { return mPhysical; }
    VkDevice device() const { return mDevice; }
    VkQueue queue() const { return mQueue; }
    std::uint32_t queueFamily() const { return mQueueFamily; }
    const DeviceInfo& info() const { return mInfo; }
    const VkPhysicalDeviceLimits& limits() const { return mLimits; }
    bool bufferDeviceAddress() const { return mBufferDeviceAddress; }
    bool geometryShader() const { return mGeometryShader; }
    // The largest single vkAllocateMemory this device accepts
    // (VkPhysicalDeviceMaintenance3Properties::maxMemoryAllocationSize). Larger allocations may
    // fail or, on some drivers, succeed and misbehave; a pool must split or refuse before that.
    VkDeviceSize maxAllocationBytes() const { return mMaxAllocationBytes; }
    // The largest VkBuffer this device can create (VkPhysicalDeviceMaintenance4Properties::
    // maxBufferSize, Vulkan 1.3 core). A buffer is also bounded by maxAllocationBytes() since each
    // Buffer owns its memory; use the smaller of the two as a buffer's size limit.
    VkDeviceSize maxBufferBytes() const { return mMaxBufferBytes; }

    // One submission waits at most this long by default: far beyond any pass, short enough to
    // report a hang instead of hanging.
    static constexpr std::uint64_t kDefaultFenceTimeoutNs = 600ull * 1000 * 1000 * 1000;

    // Records commands, submits them and waits for completion. Everything a command buffer uses
    // must stay alive until this returns, which is the simple lifetime rule of this codebase.
    // When the wait fails (timeout, device lost) it throws bl::Error and keeps the command buffer
    // and fence (the queue may still use them) until they are done or the context is destroyed.
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record,
                       std::uint64_t timeoutNs = kDefaultFenceTimeoutNs) const;

    // Memory types are chosen by vk::chooseMemoryType (vk/Buffer.h), one rule for buffers and images.

    // Size of the largest device-local memory heap.
    VkDeviceSize deviceLocalHeapBytes() const;
    // Throws a clear error when `bytes` cannot fit in device memory, before any allocation is tried
    // (an impossible request must be an error, not an out-of-memory crash). `what` names the user.
    void requireDeviceMemory(VkDeviceSize bytes, const std::string& what) const;

    // Validation messages of severity error since creation (always 0 without validation).
    std::size_t validationErrorCount() const;
    std::vector<std::string> validationErrors() const;

    // Destroys the device and the instance now, with the validation messenger alive until the end
    // so that objects still alive are reported (and counted) as errors; validationErrorCount()
    // stays readable afterwards. The context cannot be used again.
    void close() { release(); }
    // All Vulkan 1.3 devices, for `--device` help and listing.
    static std::vector<DeviceInfo> listDevices();

private:
    void release(); // destroys what exists, in reverse order of creation
    // Frees the command buffers and fences of submissions whose wait failed, once they finished.
    void reclaimFinishedSubmissions() const;

    static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT types,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                     void* self);

    VkInstance mInstance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT mMessenger = VK_NULL_HANDLE;
    VkPhysicalDevice mPhysical = VK_NULL_HANDLE;
    VkDevice mDevice = VK_NULL_HANDLE;
    VkQueue mQueue = VK_NULL_HANDLE;
    std::uint32_t mQueueFamily = 0;
    VkCommandPool mCommandPool = VK_NULL_HANDLE;
    DeviceInfo mInfo;
    VkPhysicalDeviceLimits mLimits{};
    bool mBufferDeviceAddress = false;
    bool mGeometryShader = false;
    VkDeviceSize mMaxAllocationBytes = 0;
    VkDeviceSize mMaxBufferBytes = 0;

    // Submissions whose wait failed: freed by reclaimFinishedSubmissions() or release().
    struct AbandonedSubmission {
        VkCommandBuffer commandBuffer = VK_NULL_HANDLE;
        VkFence fence = VK_NULL_HANDLE;
    };
    mutable std::mutex mAbandonedMutex;
    mutable std::vector<AbandonedSubmission> mAbandoned;

    mutable std::mutex mMessageMutex;
    std::vector<std::string> mErrors;
};

} // namespace bl::vk
