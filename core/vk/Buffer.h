// GPU buffers reached by device address (no descriptor binding limit caps their size), with upload and
// download through a staging buffer, or directly where device memory is host-visible (lavapipe, UMA GPUs)
// and the context is not in discrete-memory mode (Context::mapsDeviceMemory).
#pragma once

#include "core/vk/Context.h"

#include <cstddef>
#include <span>
#include <string>

namespace ripple::vk {

class Buffer {
public:
    enum class Placement { Device, HostStaging };

    Buffer() = default;
    // Device-local storage buffer with a device address. Throws VulkanError naming `name` and the size when
    // the allocation fails (VK_ERROR_OUT_OF_DEVICE_MEMORY and friends).
    Buffer(const Context& context, VkDeviceSize size, const std::string& name,
           VkBufferUsageFlags extraUsage = 0, Placement placement = Placement::Device);
    ~Buffer();
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    VkDeviceAddress address() const { return address_; }
    const std::string& name() const { return name_; }
    explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }
    // The host reads and writes it in place (HostStaging buffers, and device buffers where the context maps
    // device memory); false: upload and download copy through a staging buffer.
    bool isMapped() const { return mapped_ != nullptr; }

    void upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
    void download(void* data, VkDeviceSize bytes, VkDeviceSize offset = 0) const;
    template <class T> void upload(std::span<const T> items) { upload(items.data(), items.size_bytes()); }
    template <class T> void download(std::span<T> items) const { download(items.data(), items.size_bytes()); }

private:
    void release();

    const Context* context_ = nullptr;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    VkDeviceAddress address_ = 0;
    void* mapped_ = nullptr;  // non-null where device memory is host-visible: no staging needed
    std::string name_;
};

// Device address of a buffer that may be absent (0 stands for "none" in kernel parameters).
inline VkDeviceAddress addressOf(const Buffer& buffer) { return buffer ? buffer.address() : 0; }

}  // namespace ripple::vk
