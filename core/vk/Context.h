// A headless Vulkan compute context: instance, the chosen physical device (discrete GPU, then integrated,
// then CPU, one per node-local rank: DeviceChoice.h; RIPPLE_VK_DEVICE=<index or name substring> overrides),
// one compute queue, a pipeline cache, the
// compute pipelines built on it, and one-shot command submission. Validation layers and a message counter
// when asked (tests do). Discrete-memory mode (RIPPLE_VK_DISCRETE_MEMORY=1) runs a CPU device's buffers
// through the staging path a discrete GPU takes.
#pragma once

#include "core/vk/Check.h"
#include "core/vk/DeviceChoice.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace ripple::vk {

struct ContextOptions {
    bool validation = false;      // enable VK_LAYER_KHRONOS_validation; every message is counted
    bool printDeviceChoice = true;
    std::string deviceOverride;   // index or name substring; empty: take RIPPLE_VK_DEVICE from the environment
    std::string deviceOverrideSource = "ContextOptions::deviceOverride";  // names it in messages
    // This process among the processes of its node (an MPI rank's node-local rank, which mpi/ finds): without
    // an override it takes the (localRank mod n)-th of the node's n devices of the best kind.
    uint32_t localRank = 0;
    uint32_t localRankCount = 1;
    // Enable VK_KHR_acceleration_structure and VK_KHR_ray_query where the device has them (the ray-query
    // traversal back-end); false makes the context behave as a device without them (tests of that path).
    bool rayQuery = true;
    // Treat device memory as memory the host cannot map, as on a discrete GPU: every upload and download of a
    // device buffer goes through a staging buffer (Buffer.h), which a CPU device or an integrated GPU would
    // otherwise never run. Buffers placed HostStaging stay mapped, as on a discrete GPU. Unset: the
    // environment's RIPPLE_VK_DISCRETE_MEMORY (1 on, 0 or unset off).
    std::optional<bool> discreteMemory;
    // Lowers the limits properties() reports, "key=value,..." (LimitsOverride.h), so that the code that splits
    // work to fit them runs on devices with generous ones. Unset: the environment's RIPPLE_VK_LIMITS.
    std::optional<std::string> limits;
};

// The device a Context made with `options` takes among `devices` (in the instance's order): its override,
// else RIPPLE_VK_DEVICE, else the node-local rank's device of the best kind (vk::chooseDevice).
DeviceChoice chooseDevice(std::span<const DeviceDescription> devices, const ContextOptions& options);

// Entry points of VK_KHR_acceleration_structure, loaded with vkGetDeviceProcAddr (the loader does not
// export extension commands). All null unless Context::supportsRayQuery().
struct AccelerationStructureFunctions {
    PFN_vkCreateAccelerationStructureKHR create = nullptr;
    PFN_vkDestroyAccelerationStructureKHR destroy = nullptr;
    PFN_vkGetAccelerationStructureBuildSizesKHR buildSizes = nullptr;
    PFN_vkCmdBuildAccelerationStructuresKHR cmdBuild = nullptr;
    PFN_vkGetAccelerationStructureDeviceAddressKHR deviceAddress = nullptr;
    PFN_vkCmdWriteAccelerationStructuresPropertiesKHR cmdWriteProperties = nullptr;
    PFN_vkCmdCopyAccelerationStructureKHR cmdCopy = nullptr;
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
    // The device's properties, with its limits lowered by ContextOptions::limits / RIPPLE_VK_LIMITS: every
    // dispatch, push constant block and split of work is sized by these.
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    const VkPhysicalDeviceMemoryProperties& memoryProperties() const { return memoryProperties_; }
    const std::string& deviceName() const { return deviceName_; }
    // The chosen device's index among those the instance lists (vk::listDevices has the same order).
    uint32_t deviceIndex() const { return deviceIndex_; }
    // The driver's name and version as it reports them, e.g. "llvmpipe Mesa 25.0.7 (LLVM 15.0.6)".
    const std::string& driverVersion() const { return driverVersion_; }
    bool isCpuDevice() const { return properties_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }

    // Whether buffers placed on the device are host-mapped (CPU devices and integrated GPUs, whose device
    // memory is host-visible) rather than reached through staging buffers. False in discrete-memory mode.
    bool mapsDeviceMemory() const { return mapsDeviceMemory_; }
    bool discreteMemoryMode() const { return discreteMemory_; }
    // Uploads and downloads that went through a staging buffer so far (Buffer counts them): tests check
    // which path ran.
    uint64_t stagedTransferCount() const { return stagedTransfers_.load(); }
    void countStagedTransfer() const { ++stagedTransfers_; }

    // Ray queries: VK_KHR_acceleration_structure, VK_KHR_ray_query and VK_KHR_deferred_host_operations
    // with the accelerationStructure and rayQuery features, all enabled on this device.
    bool supportsRayQuery() const { return rayQuery_; }
    // What this device lacks for ray queries ("VK_KHR_ray_query, rayQuery feature"); empty when supported.
    const std::string& rayQueryMissing() const { return rayQueryMissing_; }
    const AccelerationStructureFunctions& accelerationStructureFunctions() const { return asFunctions_; }
    // VkPhysicalDeviceAccelerationStructurePropertiesKHR::minAccelerationStructureScratchOffsetAlignment.
    VkDeviceSize accelerationStructureScratchAlignment() const { return scratchAlignment_; }

    // Index of a memory type with all of `required` among `typeBits`, preferring one that also has `preferred`.
    uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred = 0) const;

    // Records commands with `record`, submits them and waits. Used for uploads and for kernel launches alike.
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;

    // Attaches a debug name to any Vulkan object (shows in validation messages and GPU debuggers).
    void setName(VkObjectType type, uint64_t handle, const std::string& name) const;

    // Compute pipelines are built once per device and kept until it is destroyed (ComputePipeline's
    // constructor looks them up here): building one costs lavapipe up to tens of milliseconds, its
    // VkPipelineCache keeps nothing, and every PathTracer (one per ANARI frame, one per test render) asks for
    // the same kernels again. `key` tells the pipelines apart (ComputePipeline makes it from the SPIR-V's
    // words, the push constant size and the specialization constants); `build` makes the one not stored yet.
    // Safe to call from several threads.
    struct StoredPipeline {
        VkPipeline pipeline = VK_NULL_HANDLE;
        VkPipelineLayout layout = VK_NULL_HANDLE;
    };
    StoredPipeline storedPipeline(const std::string& key, const std::function<StoredPipeline()>& build) const;
    size_t storedPipelineCount() const;

    // Validation messages seen so far (warnings and errors); tests require zero.
    uint64_t validationMessageCount() const { return validationMessages_.load(); }
    std::string lastValidationMessage() const;

private:
    static VkBool32 VKAPI_PTR onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT*, void*);
    void choosePhysicalDevice(const ContextOptions& options);
    // Checks the ray-query extensions and features; fills `extensions` and the feature chain to enable.
    void probeRayQuery(const ContextOptions& options, std::vector<const char*>& extensions);
    void loadAccelerationStructureFunctions();
    void destroy();

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memoryProperties_{};
    std::string deviceName_;
    uint32_t deviceIndex_ = 0;
    std::string driverVersion_;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    VkCommandPool commandPool_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkPipelineCache pipelineCache_ = VK_NULL_HANDLE;
    PFN_vkSetDebugUtilsObjectNameEXT setObjectName_ = nullptr;
    bool rayQuery_ = false;
    std::string rayQueryMissing_;
    AccelerationStructureFunctions asFunctions_;
    VkDeviceSize scratchAlignment_ = 256;
    bool discreteMemory_ = false;
    bool mapsDeviceMemory_ = false;
    mutable std::atomic<uint64_t> stagedTransfers_{0};
    std::atomic<uint64_t> validationMessages_{0};
    mutable std::mutex validationMutex_;  // the callback runs on whichever thread made the call (pipelines
    std::string lastValidationMessage_;   // are built on several at once)
    mutable std::mutex pipelinesMutex_;
    mutable std::map<std::string, StoredPipeline> pipelines_;  // see storedPipeline()
};

}  // namespace ripple::vk
