// A VkBuffer with its own memory. Host-visible buffers stay mapped for their whole life. A size
// beyond the device's largest buffer or allocation, or its heap, is a clear error before any
// allocation is tried.
#pragma once

#include "vk/Context.h"

#include <cstring>
#include <span>

namespace bl::vk {

enum class MemoryUse {
    Device,   // GPU-only; filled by upload() through a staging copy when not host-visible
    Upload,   // host-visible, written by the CPU
    Readback, // host-visible (cached where possible), read by the CPU
};

// The memory type `bytes` for `use` get among `typeBits` (VkMemoryRequirements::memoryTypeBits),
// chosen from `memory` alone so the rule can be tested on any device's layout: the types with the
// flags `use` needs, in the largest heap that has them (Device: DEVICE_LOCAL, never preferring
// HOST_VISIBLE, so VRAM wins over a discrete GPU's small BAR window). Throws a clear error when no
// type fits or `bytes` exceed that heap.
std::uint32_t chooseMemoryType(const VkPhysicalDeviceMemoryProperties& memory, std::uint32_t typeBits,
                               MemoryUse use, VkDeviceSize bytes);

class Buffer {
public:
    Buffer() = default;
    Buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use);

    VkBuffer get() const { return mBuffer.get(); }
    VkDeviceSize size() const { return mSize; }
    bool mapped() const { return mMapped != nullptr; }
    void* data() const { return mMapped; }

    // Copies bytes into the buffer at `offset`: directly when mapped, else through staging.
    void upload(const Context& ctx, const void* bytes, VkDeviceSize size, VkDeviceSize offset = 0);
    template <typename T> void upload(const Context& ctx, std::span<const T> items) {
        upload(ctx, items.data(), items.size_bytes());
    }
    // Copies the buffer's bytes back to the host.
    void download(const Context& ctx, void* bytes, VkDeviceSize size, VkDeviceSize offset = 0) const;

private:
    BufferHandle mBuffer;
    Memory mMemory;
    VkDeviceSize mSize = 0;
    void* mMapped = nullptr;
};

// A device buffer filled with `items` (at least 1 element is allocated so empty lists stay valid).
template <typename T>
Buffer makeBuffer(const Context& ctx, std::span<const T> items, VkBufferUsageFlags usage) {
    Buffer b(ctx, std::max<VkDeviceSize>(items.size_bytes(), sizeof(T)),
             usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Device);
    if (!items.empty()) {
        b.upload(ctx, items.data(), items.size_bytes());
    }
    return b;
}

} // namespace bl::vk
