// A headless Vulkan compute context: instance, the chosen physical device (discrete GPU, then integrated,
// then CPU; RIPPLE_VK_DEVICE=<index or name substring> overrides), one compute queue, a pipeline cache,
// and one-shot command submission. Validation layers and a message counter when asked (tests do).
#pragma once

#include "core/vk/Check.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace ripple::vk {

struct ContextOptions {
    bool validation = false;      // enable VK_LAYER_KHRONOS_validation; every message is counted
    bool printDeviceChoice = true;
    std::string deviceOverride;   // empty: take RIPPLE_VK_DEVICE from the environment
};

class Context {
public:
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return queueFamily_; }
    VkPipelineCache pipelineCache() const { return pipelineCache_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    const VkPhysicalDeviceMemoryProperties& memoryProperties() const { return memoryProperties_; }
    const std::string& deviceName() const { return deviceName_; }
    bool isCpuDevice() const { return properties_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }

    // Index of a memory type with all of `required` among `typeBits`, preferring one that also has `preferred`.
    uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred = 0) const;

    // Records commands with `record`, submits them and waits. Used for uploads and for kernel launches alike.
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;

    // Attaches a debug name to any Vulkan object (shows in validation messages and GPU debuggers).
    void setName(VkObjectType type, uint64_t handle, const std::string& name) const;

    // Validation messages seen so far (warnings and errors); tests require zero.
    uint64_t validationMessageCount() const { return validationMessages_.load(); }
    const std::string& lastValidationMessage() const { return lastValidationMessage_; }

private:
    static VkBool32 VKAPI_PTR onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT*, void*);
    void choosePhysicalDevice(const ContextOptions& options);
    void destroy();

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memoryProperties_{};
    std::string deviceName_;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    VkCommandPool commandPool_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkPipelineCache pipelineCache_ = VK_NULL_HANDLE;
    PFN_vkSetDebugUtilsObjectNameEXT setObjectName_ = nullptr;
    std::atomic<uint64_t> validationMessages_{0};
    std::string lastValidationMessage_;
};

}  // namespace ripple::vk
