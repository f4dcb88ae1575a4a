// Device-address storage buffers, and the staging path for devices whose memory the host cannot map.
#include "core/vk/Buffer.h"

#include <cstring>
#include <sstream>
#include <utility>

namespace ripple::vk {

namespace {

constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                      VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStage, VkAccessFlags dstAccess) {
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = srcAccess;
    barrier.dstAccessMask = dstAccess;
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

std::string describe(const std::string& name, VkDeviceSize size) {
    std::ostringstream s;
    s << "allocating " << size << " bytes (" << static_cast<double>(size) / (1024.0 * 1024.0) << " MiB) for GPU buffer '"
      << name << "'";
    return s.str();
}

}  // namespace

Buffer::Buffer(const Context& context, VkDeviceSize size, const std::string& name, VkBufferUsageFlags extraUsage,
               Placement placement)
    : context_(&context), size_(size), name_(name) {
    const VkDevice device = context.device();
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size > 0 ? size : 16;  // Vulkan forbids empty buffers; kernels never read past `size_`
    info.usage = kUsage | extraUsage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    const VkResult created = vkCreateBuffer(device, &info, nullptr, &buffer_);
    if (created != VK_SUCCESS) throw VulkanError(describe(name, size) + ": vkCreateBuffer returned " + resultName(created), created);

    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device, buffer_, &requirements);

    // Where device memory is host-visible (CPU devices, integrated GPUs) map it and skip staging, unless the
    // context is in discrete-memory mode.
    const bool unified = context.mapsDeviceMemory();
    const VkMemoryPropertyFlags hostAccess = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    const bool staging = placement == Placement::HostStaging;
    const uint32_t type = context.memoryType(requirements.memoryTypeBits,
                                             staging ? hostAccess : VkMemoryPropertyFlags(VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT),
                                             unified ? hostAccess : VkMemoryPropertyFlags(0));

    // Refuse what cannot fit before asking the driver, so the error names the allocation rather than
    // surfacing as a validation message or a driver abort.
    const VkPhysicalDeviceMemoryProperties& memory = context.memoryProperties();
    const VkDeviceSize heapSize = memory.memoryHeaps[memory.memoryTypes[type].heapIndex].size;
    if (requirements.size > heapSize) {
        release();
        throw VulkanError(describe(name, size) + ": larger than the device's memory heap (" + std::to_string(heapSize) +
                              " bytes): VK_ERROR_OUT_OF_DEVICE_MEMORY",
                          VK_ERROR_OUT_OF_DEVICE_MEMORY);
    }

    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.pNext = &flags;
    alloc.allocationSize = requirements.size;
    alloc.memoryTypeIndex = type;
    const VkResult allocated = vkAllocateMemory(device, &alloc, nullptr, &memory_);
    if (allocated != VK_SUCCESS) {
        release();
        throw VulkanError(describe(name, size) + ": vkAllocateMemory returned " + resultName(allocated), allocated);
    }
    RIPPLE_VK_CHECK(vkBindBufferMemory(device, buffer_, memory_, 0));
    if ((memory.memoryTypes[type].propertyFlags & hostAccess) == hostAccess && (unified || staging))
        RIPPLE_VK_CHECK(vkMapMemory(device, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));

    VkBufferDeviceAddressInfo addressInfo{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    addressInfo.buffer = buffer_;
    address_ = vkGetBufferDeviceAddress(device, &addressInfo);
    context.setName(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<uint64_t>(buffer_), name);
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& other) noexcept { *this = std::move(other); }

Buffer& Buffer::operator=(Buffer&& other) noexcept {
    if (this != &other) {
        release();
        context_ = other.context_;
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        size_ = std::exchange(other.size_, 0);
        address_ = std::exchange(other.address_, 0);
        mapped_ = std::exchange(other.mapped_, nullptr);
        name_ = std::move(other.name_);
    }
    return *this;
}

void Buffer::release() {
    if (!context_) return;
    const VkDevice device = context_->device();
    if (mapped_) vkUnmapMemory(device, memory_);
    if (buffer_) vkDestroyBuffer(device, buffer_, nullptr);
    if (memory_) vkFreeMemory(device, memory_, nullptr);
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
}

void Buffer::upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
    if (bytes == 0) return;
    if (offset + bytes > size_) throw std::out_of_range("upload of " + std::to_string(bytes) + " bytes overruns buffer '" + name_ + "'");
    if (mapped_) {
        std::memcpy(static_cast<char*>(mapped_) + offset, data, bytes);
        return;
    }
    Buffer staging(*context_, bytes, name_ + " (staging)", 0, Placement::HostStaging);
    std::memcpy(staging.mapped_, data, bytes);
    context_->submitAndWait([&](VkCommandBuffer cmd) {
        // Work submitted before may still read or write the range being overwritten.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
        VkBufferCopy region{0, offset, bytes};
        vkCmdCopyBuffer(cmd, staging.buffer_, buffer_, 1, &region);
        // Submissions after this one read what the copy wrote.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
    });
    context_->countStagedTransfer();
}

void Buffer::download(void* data, VkDeviceSize bytes, VkDeviceSize offset) const {
    if (bytes == 0) return;
    if (offset + bytes > size_) throw std::out_of_range("download of " + std::to_string(bytes) + " bytes overruns buffer '" + name_ + "'");
    if (mapped_) {
        std::memcpy(data, static_cast<const char*>(mapped_) + offset, bytes);
        return;
    }
    Buffer staging(*context_, bytes, name_ + " (staging)", 0, Placement::HostStaging);
    context_->submitAndWait([&](VkCommandBuffer cmd) {
        // What submissions before this one wrote (kernels, other copies) is what the copy reads.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferCopy region{offset, 0, bytes};
        vkCmdCopyBuffer(cmd, buffer_, staging.buffer_, 1, &region);
        // A fence wait alone does not make device writes visible to the host.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                      VK_ACCESS_HOST_READ_BIT);
    });
    std::memcpy(data, staging.mapped_, bytes);
    context_->countStagedTransfer();
}

}  // namespace ripple::vk
