#include "vk/Buffer.h"

#include "base/Error.h"
#include "vk/Check.h"

namespace bl::vk {

Buffer::Buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use) : mSize(size) {
    if (size == 0) {
        throw Error("Buffer: zero size");
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
    VkMemoryPropertyFlags required = 0, preferred = 0;
    switch (use) {
    case MemoryUse::Device:
        // Device-local and host-visible (unified memory, lavapipe) saves the staging copy.
        required = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
        preferred = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        break;
    case MemoryUse::Upload:
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        break;
    case MemoryUse::Readback:
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
        break;
    }
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.pNext = (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) ? &flags : nullptr;
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = ctx.memoryType(req.memoryTypeBits, required, preferred);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    BL_VK_CHECK(vkAllocateMemory(device, &alloc, nullptr, &memory));
    mMemory = Memory(device, memory);
    BL_VK_CHECK(vkBindBufferMemory(device, raw, memory, 0));

    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &mem);
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
    });
    std::memcpy(bytes, staging.data(), size);
}

} // namespace bl::vk
