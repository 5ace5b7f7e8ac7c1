// The memory-type rule of vk::Buffer on synthetic device layouts (no Vulkan device needed): a
// discrete GPU's big VRAM heap, its small host-visible BAR window, system memory, and a unified
// device like lavapipe.
#include "support/TestFiles.h"
#include "vk/Buffer.h"

#include <gtest/gtest.h>

using namespace bl;
using bl::test::errorOf;

namespace {

constexpr VkDeviceSize kMiB = VkDeviceSize(1) << 20;
constexpr VkDeviceSize kGiB = VkDeviceSize(1) << 30;
constexpr std::uint32_t kAllTypes = ~0u;

constexpr VkMemoryPropertyFlags kDeviceLocal = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
constexpr VkMemoryPropertyFlags kHostVisible =
    VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
constexpr VkMemoryPropertyFlags kHostCached = kHostVisible | VK_MEMORY_PROPERTY_HOST_CACHED_BIT;

struct Layout {
    VkPhysicalDeviceMemoryProperties memory{};
    std::uint32_t heap(VkDeviceSize bytes, VkMemoryHeapFlags flags) {
        memory.memoryHeaps[memory.memoryHeapCount] = {bytes, flags};
        return memory.memoryHeapCount++;
    }
    std::uint32_t type(VkMemoryPropertyFlags flags, std::uint32_t heapIndex) {
        memory.memoryTypes[memory.memoryTypeCount] = {flags, heapIndex};
        return memory.memoryTypeCount++;
    }
};

// A discrete GPU without resizable BAR, in the order drivers commonly list it: the BAR type (small
// device-local, host-visible heap) comes before the plain VRAM type.
struct DiscreteGpu : Layout {
    std::uint32_t vramHeap = heap(8 * kGiB, VK_MEMORY_HEAP_DEVICE_LOCAL_BIT);
    std::uint32_t systemHeap = heap(16 * kGiB, 0);
    std::uint32_t barHeap = heap(256 * kMiB, VK_MEMORY_HEAP_DEVICE_LOCAL_BIT);
    std::uint32_t bar = type(kDeviceLocal | kHostVisible, barHeap);
    std::uint32_t vram = type(kDeviceLocal, vramHeap);
    std::uint32_t system = type(kHostVisible, systemHeap);
    std::uint32_t systemCached = type(kHostCached, systemHeap);
};

} // namespace

TEST(BufferMemory, DeviceBuffersLiveInTheLargestDeviceLocalHeapNotTheBarWindow) {
    DiscreteGpu gpu;
    EXPECT_EQ(vk::chooseMemoryType(gpu.memory, kAllTypes, vk::MemoryUse::Device, kMiB), gpu.vram);
}

TEST(BufferMemory, HostBuffersUseSystemMemoryAndReadbackPrefersCached) {
    DiscreteGpu gpu;
    EXPECT_EQ(vk::chooseMemoryType(gpu.memory, kAllTypes, vk::MemoryUse::Upload, kMiB), gpu.system);
    EXPECT_EQ(vk::chooseMemoryType(gpu.memory, kAllTypes, vk::MemoryUse::Readback, kMiB), gpu.systemCached);
}

TEST(BufferMemory, TypeBitsOfTheResourceAreHonoured) {
    DiscreteGpu gpu;
    // A resource that only the BAR type can hold still gets it: device-local is what counts.
    EXPECT_EQ(vk::chooseMemoryType(gpu.memory, 1u << gpu.bar, vk::MemoryUse::Device, kMiB), gpu.bar);
    std::string e = errorOf([&] { vk::chooseMemoryType(gpu.memory, 1u << gpu.system, vk::MemoryUse::Device, kMiB); });
    EXPECT_NE(e.find("device-local"), std::string::npos) << e;
}

TEST(BufferMemory, UnifiedMemoryKeepsItsSingleHostVisibleType) {
    Layout unified; // lavapipe and integrated GPUs: one heap, every type host-visible
    std::uint32_t heap = unified.heap(4 * kGiB, VK_MEMORY_HEAP_DEVICE_LOCAL_BIT);
    std::uint32_t only = unified.type(kDeviceLocal | kHostCached, heap);
    EXPECT_EQ(vk::chooseMemoryType(unified.memory, kAllTypes, vk::MemoryUse::Device, kMiB), only);
    EXPECT_EQ(vk::chooseMemoryType(unified.memory, kAllTypes, vk::MemoryUse::Readback, kMiB), only);
}

TEST(BufferMemory, AnAllocationBeyondItsHeapIsAClearError) {
    DiscreteGpu gpu;
    EXPECT_EQ(vk::chooseMemoryType(gpu.memory, kAllTypes, vk::MemoryUse::Device, 8 * kGiB), gpu.vram);
    std::string e = errorOf([&] { vk::chooseMemoryType(gpu.memory, kAllTypes, vk::MemoryUse::Device, 9 * kGiB); });
    EXPECT_NE(e.find("a buffer of 9216 MiB does not fit the largest device-local memory heap (8192 MiB)"),
              std::string::npos)
        << e;
    // Only the BAR type allowed: its 256 MiB heap is what the request is checked against.
    e = errorOf([&] { vk::chooseMemoryType(gpu.memory, 1u << gpu.bar, vk::MemoryUse::Device, kGiB); });
    EXPECT_NE(e.find("(256 MiB)"), std::string::npos) << e;
}
