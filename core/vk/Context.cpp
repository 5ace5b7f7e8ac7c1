#include "vk/Context.h"

#include "base/Error.h"
#include "base/Log.h"
#include "vk/Check.h"

#include <algorithm>
#include <cstring>
#include <utility>

namespace bl::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string versionString(std::uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
           std::to_string(VK_API_VERSION_PATCH(v));
}

const char* typeName(VkPhysicalDeviceType t) {
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
    }
}

int preference(VkPhysicalDeviceType t) {
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 4;
    default: return 3;
    }
}

struct Candidate {
    VkPhysicalDevice device;
    DeviceInfo info;
    VkPhysicalDeviceType type;
    std::uint32_t queueFamily;
};

std::vector<Candidate> candidates(VkInstance instance) {
    std::uint32_t n = 0;
    BL_VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, nullptr));
    std::vector<VkPhysicalDevice> devices(n);
    BL_VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, devices.data()));
    std::vector<Candidate> out;
    for (VkPhysicalDevice d : devices) {
        VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
        VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
        vkGetPhysicalDeviceProperties2(d, &props);
        if (props.properties.apiVersion < VK_API_VERSION_1_3) {
            continue;
        }
        std::uint32_t qn = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(d, &qn, nullptr);
        std::vector<VkQueueFamilyProperties> families(qn);
        vkGetPhysicalDeviceQueueFamilyProperties(d, &qn, families.data());
        std::uint32_t family = UINT32_MAX;
        for (std::uint32_t i = 0; i < qn; ++i) {
            VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
            if ((families[i].queueFlags & need) == need && families[i].timestampValidBits > 0) {
                family = i;
                break;
            }
        }
        if (family == UINT32_MAX) {
            continue;
        }
        Candidate c{d, {}, props.properties.deviceType, family};
        c.info.index = static_cast<std::uint32_t>(out.size());
        c.info.name = props.properties.deviceName;
        c.info.type = typeName(props.properties.deviceType);
        c.info.driverName = driver.driverName;
        c.info.driverInfo = driver.driverInfo;
        c.info.apiVersion = versionString(props.properties.apiVersion);
        out.push_back(c);
    }
    return out;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

const Candidate& choose(const std::vector<Candidate>& list, const std::string& wanted) {
    if (list.empty()) {
        throw Error("no Vulkan 1.3 device found (is mesa-vulkan-drivers installed?)");
    }
    if (wanted.empty()) {
        return *std::min_element(list.begin(), list.end(), [](const Candidate& a, const Candidate& b) {
            return preference(a.type) < preference(b.type);
        });
    }
    std::string names;
    for (const Candidate& c : list) {
        names += "\n  " + std::to_string(c.info.index) + ": " + c.info.name;
    }
    if (std::all_of(wanted.begin(), wanted.end(), [](unsigned char ch) { return std::isdigit(ch); })) {
        std::size_t i = std::stoul(wanted);
        if (i >= list.size()) {
            throw Error("--device " + wanted + ": no such device; available:" + names);
        }
        return list[i];
    }
    for (const Candidate& c : list) {
        if (lower(c.info.name).find(lower(wanted)) != std::string::npos) {
            return c;
        }
    }
    throw Error("--device '" + wanted + "': no device name contains it; available:" + names);
}

bool layerAvailable(const char* name) {
    std::uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    return std::any_of(layers.begin(), layers.end(),
                       [name](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

VkInstance createInstance(bool validation, const std::vector<std::string>& extraExtensions = {}) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "bundlelab";
    app.pEngineName = "bundlelab";
    app.apiVersion = VK_API_VERSION_1_3;
    std::vector<const char*> layers, extensions;
    if (validation) {
        if (!layerAvailable(kValidationLayer)) {
            throw Error(std::string("validation requested but ") + kValidationLayer +
                        " is not installed (apt install vulkan-validationlayers)");
        }
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    for (const std::string& e : extraExtensions) extensions.push_back(e.c_str());
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkInstance instance = VK_NULL_HANDLE;
    BL_VK_CHECK(vkCreateInstance(&info, nullptr, &instance));
    return instance;
}

} // namespace

std::string DeviceInfo::describe() const {
    return name + " (" + type + "), driver " + driverName + " " + driverInfo + ", Vulkan " + apiVersion;
}

std::vector<DeviceInfo> Context::listDevices() {
    VkInstance instance = createInstance(false);
    std::vector<DeviceInfo> out;
    try {
        for (const Candidate& c : candidates(instance)) {
            out.push_back(c.info);
        }
    } catch (...) {
        vkDestroyInstance(instance, nullptr);
        throw;
    }
    vkDestroyInstance(instance, nullptr);
    return out;
}

VkBool32 Context::onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                            const VkDebugUtilsMessengerCallbackDataEXT* data, void* self) {
    auto* ctx = static_cast<Context*>(self);
    std::string message = data && data->pMessage ? data->pMessage : "(no message)";
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        std::lock_guard lock(ctx->mMessageMutex);
        ctx->mErrors.push_back(message);
        log::error("validation: " + message);
    } else if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        log::warn("validation: " + message);
    }
    return VK_FALSE;
}

Context::Context(const ContextOptions& options) {
    try {
        mInstance = createInstance(options.validation, options.instanceExtensions);
        if (options.validation) {
            VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
            info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
            info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
            info.pfnUserCallback = &Context::onMessage;
            info.pUserData = this;
            auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(mInstance, "vkCreateDebugUtilsMessengerEXT"));
            if (!create) {
                throw Error("VK_EXT_debug_utils is not available");
            }
            BL_VK_CHECK(create(mInstance, &info, nullptr, &mMessenger));
        }

        const std::vector<Candidate> list = candidates(mInstance);
        const Candidate& chosen = choose(list, options.device);
        mPhysical = chosen.device;
        mInfo = chosen.info;
        mQueueFamily = chosen.queueFamily;
        VkPhysicalDeviceMaintenance4Properties maintenance4{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_PROPERTIES};
        VkPhysicalDeviceMaintenance3Properties maintenance3{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES, &maintenance4};
        VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &maintenance3};
        vkGetPhysicalDeviceProperties2(mPhysical, &props);
        mLimits = props.properties.limits;
        mMaxAllocationBytes = maintenance3.maxMemoryAllocationSize;
        mMaxBufferBytes = maintenance4.maxBufferSize;

        // Features every mode may rely on; missing required ones make a clear error.
        VkPhysicalDeviceVulkan13Features have13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        VkPhysicalDeviceVulkan12Features have12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &have13};
        VkPhysicalDeviceFeatures2 have{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &have12};
        vkGetPhysicalDeviceFeatures2(mPhysical, &have);
        auto require = [&](VkBool32 supported, const char* name) {
            if (!supported) {
                throw Error("device '" + mInfo.name + "' lacks required feature " + name);
            }
        };
        require(have13.dynamicRendering, "dynamicRendering");
        require(have13.synchronization2, "synchronization2");
        require(have13.maintenance4, "maintenance4");
        require(have.features.fragmentStoresAndAtomics, "fragmentStoresAndAtomics");

        VkPhysicalDeviceVulkan13Features use13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        use13.dynamicRendering = VK_TRUE;
        use13.synchronization2 = VK_TRUE;
        // Required by Vulkan 1.3; glslang emits LocalSizeId (which needs it) for SPIR-V 1.6.
        use13.maintenance4 = VK_TRUE;
        VkPhysicalDeviceVulkan12Features use12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &use13};
        use12.bufferDeviceAddress = have12.bufferDeviceAddress;
        use12.hostQueryReset = have12.hostQueryReset;
        use12.scalarBlockLayout = have12.scalarBlockLayout;
        mBufferDeviceAddress = have12.bufferDeviceAddress;
        VkPhysicalDeviceFeatures2 use{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &use12};
        use.features.fragmentStoresAndAtomics = VK_TRUE;
        use.features.vertexPipelineStoresAndAtomics = have.features.vertexPipelineStoresAndAtomics;
        use.features.shaderInt64 = have.features.shaderInt64;
        use.features.geometryShader = have.features.geometryShader; // gl_PrimitiveID in fragments
        mGeometryShader = have.features.geometryShader;
        use.features.shaderStorageImageWriteWithoutFormat = have.features.shaderStorageImageWriteWithoutFormat;

        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queueInfo.queueFamilyIndex = mQueueFamily;
        queueInfo.queueCount = 1;
        queueInfo.pQueuePriorities = &priority;
        VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &use};
        deviceInfo.queueCreateInfoCount = 1;
        deviceInfo.pQueueCreateInfos = &queueInfo;
        const char* swapchainExtension = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
        if (options.swapchain) {
            deviceInfo.enabledExtensionCount = 1;
            deviceInfo.ppEnabledExtensionNames = &swapchainExtension;
        }
        BL_VK_CHECK(vkCreateDevice(mPhysical, &deviceInfo, nullptr, &mDevice));
        vkGetDeviceQueue(mDevice, mQueueFamily, 0, &mQueue);

        VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
        poolInfo.queueFamilyIndex = mQueueFamily;
        BL_VK_CHECK(vkCreateCommandPool(mDevice, &poolInfo, nullptr, &mCommandPool));
    } catch (...) {
        release();
        throw;
    }
}

Context::~Context() { release(); }

void Context::release() {
    if (mDevice) {
        // After the device is idle (or lost), abandoned submissions hold nothing any more.
        vkDeviceWaitIdle(mDevice);
        for (const AbandonedSubmission& a : mAbandoned) {
            vkDestroyFence(mDevice, a.fence, nullptr); // command buffers go with their pool
        }
        mAbandoned.clear();
        if (mCommandPool) {
            vkDestroyCommandPool(mDevice, mCommandPool, nullptr);
            mCommandPool = VK_NULL_HANDLE;
        }
        vkDestroyDevice(mDevice, nullptr);
        mDevice = VK_NULL_HANDLE;
    }
    if (mMessenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(mInstance, "vkDestroyDebugUtilsMessengerEXT"));
        destroy(mInstance, mMessenger, nullptr);
        mMessenger = VK_NULL_HANDLE;
    }
    if (mInstance) {
        vkDestroyInstance(mInstance, nullptr);
        mInstance = VK_NULL_HANDLE;
    }
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record, std::uint64_t timeoutNs) const {
    reclaimFinishedSubmissions();
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = mCommandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    BL_VK_CHECK(vkAllocateCommandBuffers(mDevice, &alloc, &cmd));
    // Frees the command buffer and fence on every exit except a failed wait, where the queue may
    // still hold them.
    struct FreeOnExit {
        VkDevice d;
        VkCommandPool p;
        AbandonedSubmission s;
        ~FreeOnExit() {
            if (s.fence) {
                vkDestroyFence(d, s.fence, nullptr);
            }
            if (s.commandBuffer) {
                vkFreeCommandBuffers(d, p, 1, &s.commandBuffer);
            }
        }
    } freeOnExit{mDevice, mCommandPool, {cmd, VK_NULL_HANDLE}};

    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    BL_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    BL_VK_CHECK(vkEndCommandBuffer(cmd));

    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    BL_VK_CHECK(vkCreateFence(mDevice, &fenceInfo, nullptr, &freeOnExit.s.fence));
    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    // A failed submit leaves the command buffer and fence untouched (the spec guarantees it), so
    // they are freed as usual.
    BL_VK_CHECK(vkQueueSubmit2(mQueue, 1, &submit, freeOnExit.s.fence));
    const VkResult waited = vkWaitForFences(mDevice, 1, &freeOnExit.s.fence, VK_TRUE, timeoutNs);
    if (waited != VK_SUCCESS) {
        // Timeout or device loss: the queue may still execute (or hold) the command buffer and
        // signal the fence, so neither may be freed now. Keep both until the fence signals or the
        // context is destroyed (after vkDeviceWaitIdle).
        {
            std::lock_guard lock(mAbandonedMutex);
            mAbandoned.push_back(std::exchange(freeOnExit.s, AbandonedSubmission{}));
        }
        const std::string what = std::string("the GPU did not finish a submission (vkWaitForFences: ") +
                                 resultName(waited) + " after " + std::to_string(timeoutNs / 1000000) +
                                 " ms) on '" + mInfo.name + "'";
        log::error(what + "; its command buffer and fence are kept until the device is idle");
        throw Error(what + ". Resources that submission used must outlive it; if the device hangs, "
                           "restart the program");
    }
}

void Context::reclaimFinishedSubmissions() const {
    std::lock_guard lock(mAbandonedMutex);
    std::erase_if(mAbandoned, [&](const AbandonedSubmission& a) {
        if (vkGetFenceStatus(mDevice, a.fence) != VK_SUCCESS) {
            return false; // still running, or the device is lost: keep until release()
        }
        vkFreeCommandBuffers(mDevice, mCommandPool, 1, &a.commandBuffer);
        vkDestroyFence(mDevice, a.fence, nullptr);
        return true;
    });
}

VkDeviceSize Context::deviceLocalHeapBytes() const {
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(mPhysical, &mem);
    VkDeviceSize largest = 0;
    for (std::uint32_t i = 0; i < mem.memoryHeapCount; ++i) {
        if (mem.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) {
            largest = std::max(largest, mem.memoryHeaps[i].size);
        }
    }
    return largest;
}

void Context::requireDeviceMemory(VkDeviceSize bytes, const std::string& what) const {
    const VkDeviceSize heap = deviceLocalHeapBytes();
    if (bytes > heap) {
        auto mib = [](VkDeviceSize b) { return std::to_string((b + (1u << 20) - 1) >> 20); };
        throw Error(what + " needs " + mib(bytes) + " MiB of device memory, more than the " + mib(heap) +
                    " MiB heap of '" + mInfo.name + "'");
    }
}

std::size_t Context::validationErrorCount() const {
    std::lock_guard lock(mMessageMutex);
    return mErrors.size();
}

std::vector<std::string> Context::validationErrors() const {
    std::lock_guard lock(mMessageMutex);
    return mErrors;
}

} // namespace bl::vk
