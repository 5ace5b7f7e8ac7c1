#include "vk/Buffer.h"

#include "base/Error.h"
#include "vk/Check.h"
#include "vk/Commands.h"

#include <algorithm>
#include <cstdio>

namespace bl::vk {
namespace {

std::string hexBits(std::uint32_t bits) {
    char text[sizeof(bits) * 2 + 1];
    std::snprintf(text, sizeof(text), "%x", bits);
    return text;
}

std::string mebibytes(VkDeviceSize bytes) {
    constexpr VkDeviceSize kMiB = VkDeviceSize(1) << 20;
    return std::to_string((bytes + kMiB - 1) / kMiB);
}

} // namespace

std::uint32_t chooseMemoryType(const VkPhysicalDeviceMemoryProperties& mem, std::uint32_t typeBits,
                               MemoryUse use, VkDeviceSize bytes) {
    VkMemoryPropertyFlags required = 0, preferred = 0;
    const char* what = "";
    switch (use) {
    case MemoryUse::Device:
        // Device-local only: host visibility is not asked for, so a discrete GPU's small
        // host-visible BAR window is never chosen over its VRAM heap. Unified memory (lavapipe,
        // integrated GPUs) is host-visible anyway, and Buffer maps it to skip the staging copy.
        required = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
        what = "device-local";
        break;
    case MemoryUse::Upload:
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        what = "host-visible coherent";
        break;
    case MemoryUse::Readback:
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT; // the CPU reads it back: cached is faster
        what = "host-visible coherent";
        break;
    }
    // Among the types with the wanted flags, the one in the largest heap (so the small BAR heap
    // loses to VRAM for device buffers and to system memory for host buffers); within one heap the
    // lowest index, which Vulkan orders to have the fewest extra flags.
    for (VkMemoryPropertyFlags want : {required | preferred, required}) {
        std::uint32_t best = UINT32_MAX;
        for (std::uint32_t i = 0; i < mem.memoryTypeCount; ++i) {
            if (!(typeBits & (1u << i)) || (mem.memoryTypes[i].propertyFlags & want) != want) {
                continue;
            }
            if (best == UINT32_MAX || mem.memoryHeaps[mem.memoryTypes[i].heapIndex].size >
                                          mem.memoryHeaps[mem.memoryTypes[best].heapIndex].size) {
                best = i;
            }
        }
        if (best == UINT32_MAX) {
            continue;
        }
        const VkDeviceSize heap = mem.memoryHeaps[mem.memoryTypes[best].heapIndex].size;
        if (bytes > heap) {
            throw Error("a buffer of " + mebibytes(bytes) + " MiB does not fit the largest " + what +
                        " memory heap (" + mebibytes(heap) + " MiB)");
        }
        return best;
    }
    throw Error(std::string("no ") + what + " Vulkan memory type among the resource's types (bits 0x" +
                hexBits(typeBits) + ")");
}

Buffer::Buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use) : mSize(size) {
    if (size == 0) {
        throw Error("Buffer: zero size");
    }
    // Each Buffer owns its memory, so both the buffer and the allocation limit bound its size.
    const VkDeviceSize largest = std::min(ctx.maxBufferBytes(), ctx.maxAllocationBytes());
    if (size > largest) {
        throw Error("a buffer of " + mebibytes(size) + " MiB exceeds the largest buffer of '" + ctx.info().name +
                    "' (" + mebibytes(largest) + " MiB)");
    }
    VkDevice device = ctx.device();
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer raw = VK_NULL_HANDLE;
    BL_VK_CHECK(vkCreateBuffer(device, &info, nullptr, &raw));
    mBuffer = BufferHandle(device, raw);

    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, raw, &req);
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.pNext = (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) ? &flags : nullptr;
    alloc.allocationSize = req.size;
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &mem);
    alloc.memoryTypeIndex = chooseMemoryType(mem, req.memoryTypeBits, use, req.size);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    BL_VK_CHECK(vkAllocateMemory(device, &alloc, nullptr, &memory));
    mMemory = Memory(device, memory);
    BL_VK_CHECK(vkBindBufferMemory(device, raw, memory, 0));

    VkMemoryPropertyFlags got = mem.memoryTypes[alloc.memoryTypeIndex].propertyFlags;
    if ((got & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) && (got & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)) {
        BL_VK_CHECK(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mMapped));
    }
}

void Buffer::upload(const Context& ctx, const void* bytes, VkDeviceSize size, VkDeviceSize offset) {
    if (offset + size > mSize) {
        throw Error("Buffer::upload: " + std::to_string(offset + size) + " bytes into a buffer of " +
                    std::to_string(mSize));
    }
    if (mMapped) {
        std::memcpy(static_cast<char*>(mMapped) + offset, bytes, size);
        return;
    }
    Buffer staging(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload);
    std::memcpy(staging.data(), bytes, size);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, offset, size};
        vkCmdCopyBuffer(cmd, staging.get(), get(), 1, &region);
    });
}

void Buffer::download(const Context& ctx, void* bytes, VkDeviceSize size, VkDeviceSize offset) const {
    if (offset + size > mSize) {
        throw Error("Buffer::download: " + std::to_string(offset + size) + " bytes from a buffer of " +
                    std::to_string(mSize));
    }
    if (mMapped) {
        std::memcpy(bytes, static_cast<const char*>(mMapped) + offset, size);
        return;
    }
    Buffer staging(ctx, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{offset, 0, size};
        vkCmdCopyBuffer(cmd, get(), staging.get(), 1, &region);
        // The fence alone does not make device writes visible to host reads.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_HOST_BIT);
    });
    std::memcpy(bytes, staging.data(), size);
}

} // namespace bl::vk
