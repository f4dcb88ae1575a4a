// Instance, physical-device choice, logical device and one-shot submission for Ripple's compute work.
#include "core/vk/Context.h"

#include "core/vk/DeviceChoice.h"
#include "core/vk/LimitsOverride.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <sstream>
#include <type_traits>

namespace ripple::vk {

const char* resultName(VkResult result) {
    switch (result) {
#define RIPPLE_RESULT_CASE(name) case name: return #name;
        RIPPLE_RESULT_CASE(VK_SUCCESS)
        RIPPLE_RESULT_CASE(VK_NOT_READY)
        RIPPLE_RESULT_CASE(VK_TIMEOUT)
        RIPPLE_RESULT_CASE(VK_INCOMPLETE)
        RIPPLE_RESULT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        RIPPLE_RESULT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        RIPPLE_RESULT_CASE(VK_ERROR_INITIALIZATION_FAILED)
        RIPPLE_RESULT_CASE(VK_ERROR_DEVICE_LOST)
        RIPPLE_RESULT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        RIPPLE_RESULT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        RIPPLE_RESULT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        RIPPLE_RESULT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        RIPPLE_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        RIPPLE_RESULT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        RIPPLE_RESULT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        RIPPLE_RESULT_CASE(VK_ERROR_FRAGMENTED_POOL)
        RIPPLE_RESULT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        RIPPLE_RESULT_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
        RIPPLE_RESULT_CASE(VK_ERROR_FRAGMENTATION)
        RIPPLE_RESULT_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
        RIPPLE_RESULT_CASE(VK_PIPELINE_COMPILE_REQUIRED)
#undef RIPPLE_RESULT_CASE
    default: return "VkResult(unknown)";
    }
}

void throwVulkanError(const char* call, VkResult result, const char* file, int line) {
    std::ostringstream message;
    message << call << " failed with " << resultName(result) << " (" << static_cast<int>(result) << ") at " << file
            << ":" << line;
    throw VulkanError(message.str(), result);
}

namespace {

const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool hasLayer(const char* name) {
    uint32_t count = 0;
    RIPPLE_VK_CHECK(vkEnumerateInstanceLayerProperties(&count, nullptr));
    std::vector<VkLayerProperties> layers(count);
    RIPPLE_VK_CHECK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
    return std::any_of(layers.begin(), layers.end(), [&](const auto& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool hasInstanceExtension(const char* name) {
    uint32_t count = 0;
    RIPPLE_VK_CHECK(vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr));
    std::vector<VkExtensionProperties> extensions(count);
    RIPPLE_VK_CHECK(vkEnumerateInstanceExtensionProperties(nullptr, &count, extensions.data()));
    return std::any_of(extensions.begin(), extensions.end(),
                       [&](const auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// ContextOptions::discreteMemory, else RIPPLE_VK_DISCRETE_MEMORY: 1 on, 0 or unset off; anything else is
// refused, so that a mistyped value does not silently test the mapped path.
bool discreteMemoryWanted(const ContextOptions& options) {
    if (options.discreteMemory) return *options.discreteMemory;
    const char* env = std::getenv("RIPPLE_VK_DISCRETE_MEMORY");
    if (!env || !*env || std::strcmp(env, "0") == 0) return false;
    if (std::strcmp(env, "1") == 0) return true;
    throw std::runtime_error(std::string("RIPPLE_VK_DISCRETE_MEMORY=") + env + " is neither 1 (on) nor 0 (off)");
}

std::mutex& submitMutex() {
    static std::mutex mutex;
    return mutex;
}

}  // namespace

VkBool32 VKAPI_PTR Context::onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                           VkDebugUtilsMessageTypeFlagsEXT, const VkDebugUtilsMessengerCallbackDataEXT* data,
                                           void* user) {
    auto* self = static_cast<Context*>(user);
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        const std::string message = data->pMessage ? data->pMessage : "";
        std::fprintf(stderr, "ripple: Vulkan validation: %s\n", message.c_str());
        std::lock_guard lock(self->validationMutex_);
        self->lastValidationMessage_ = message;
        self->validationMessages_++;
    }
    return VK_FALSE;
}

std::string Context::lastValidationMessage() const {
    std::lock_guard lock(validationMutex_);
    return lastValidationMessage_;
}

Context::Context(const ContextOptions& options) {
    const bool debugUtils = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (options.validation && !hasLayer(kValidationLayer))
        throw std::runtime_error(std::string("Vulkan validation was requested but ") + kValidationLayer +
                                 " is not installed (Debian package vulkan-validationlayers)");

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "ripple";
    app.pEngineName = "ripple";
    app.apiVersion = VK_API_VERSION_1_2;

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    if (options.validation) layers.push_back(kValidationLayer);
    if (debugUtils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = &Context::onDebugMessage;
    messengerInfo.pUserData = this;

    VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instanceInfo.pApplicationInfo = &app;
    instanceInfo.enabledLayerCount = static_cast<uint32_t>(layers.size());
    instanceInfo.ppEnabledLayerNames = layers.data();
    instanceInfo.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    instanceInfo.ppEnabledExtensionNames = extensions.data();
    if (options.validation && debugUtils) instanceInfo.pNext = &messengerInfo;  // also covers instance creation
    RIPPLE_VK_CHECK(vkCreateInstance(&instanceInfo, nullptr, &instance_));

    try {
        if (options.validation && debugUtils) {
            auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
            RIPPLE_VK_CHECK(create(instance_, &messengerInfo, nullptr, &messenger_));
        }
        if (debugUtils)
            setObjectName_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
                vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));

        choosePhysicalDevice(options);

        uint32_t familyCount = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, nullptr);
        std::vector<VkQueueFamilyProperties> families(familyCount);
        vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, families.data());
        queueFamily_ = familyCount;
        for (uint32_t i = 0; i < familyCount; ++i)
            if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) { queueFamily_ = i; break; }
        if (queueFamily_ == familyCount) throw std::runtime_error("Vulkan device " + deviceName_ + " has no compute queue");

        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queueInfo.queueFamilyIndex = queueFamily_;
        queueInfo.queueCount = 1;
        queueInfo.pQueuePriorities = &priority;

        VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        features12.bufferDeviceAddress = VK_TRUE;
        features12.hostQueryReset = VK_TRUE;
        VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        features.pNext = &features12;
        features.features.shaderInt64 = VK_TRUE;

        std::vector<const char*> deviceExtensions;
        probeRayQuery(options, deviceExtensions);
        VkPhysicalDeviceAccelerationStructureFeaturesKHR asFeatures{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
        VkPhysicalDeviceRayQueryFeaturesKHR rayQueryFeatures{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
        if (rayQuery_) {
            asFeatures.accelerationStructure = VK_TRUE;
            rayQueryFeatures.rayQuery = VK_TRUE;
            features12.pNext = &asFeatures;
            asFeatures.pNext = &rayQueryFeatures;
        }

        VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        deviceInfo.pNext = &features;
        deviceInfo.queueCreateInfoCount = 1;
        deviceInfo.pQueueCreateInfos = &queueInfo;
        deviceInfo.enabledExtensionCount = static_cast<uint32_t>(deviceExtensions.size());
        deviceInfo.ppEnabledExtensionNames = deviceExtensions.data();
        RIPPLE_VK_CHECK(vkCreateDevice(physicalDevice_, &deviceInfo, nullptr, &device_));
        vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
        if (rayQuery_) loadAccelerationStructureFunctions();

        VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        poolInfo.queueFamilyIndex = queueFamily_;
        RIPPLE_VK_CHECK(vkCreateCommandPool(device_, &poolInfo, nullptr, &commandPool_));
        VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        RIPPLE_VK_CHECK(vkCreateFence(device_, &fenceInfo, nullptr, &fence_));
        VkPipelineCacheCreateInfo cacheInfo{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
        RIPPLE_VK_CHECK(vkCreatePipelineCache(device_, &cacheInfo, nullptr, &pipelineCache_));
        setName(VK_OBJECT_TYPE_QUEUE, reinterpret_cast<uint64_t>(queue_), "ripple compute queue");
        setName(VK_OBJECT_TYPE_PIPELINE_CACHE, reinterpret_cast<uint64_t>(pipelineCache_), "ripple pipeline cache");
    } catch (...) {
        destroy();  // the destructor does not run when a constructor throws
        throw;
    }
}

DeviceChoice chooseDevice(std::span<const DeviceDescription> devices, const ContextOptions& options) {
    if (!options.deviceOverride.empty())
        return chooseDevice(devices, options.localRank, options.localRankCount, options.deviceOverride,
                            options.deviceOverrideSource);
    const char* env = std::getenv("RIPPLE_VK_DEVICE");
    return chooseDevice(devices, options.localRank, options.localRankCount, env ? env : "", "RIPPLE_VK_DEVICE");
}

void Context::choosePhysicalDevice(const ContextOptions& options) {
    uint32_t count = 0;
    RIPPLE_VK_CHECK(vkEnumeratePhysicalDevices(instance_, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    RIPPLE_VK_CHECK(vkEnumeratePhysicalDevices(instance_, &count, devices.data()));
    const DeviceChoice chosen = chooseDevice(describeDevices(instance_), options);

    deviceIndex_ = chosen.index;
    physicalDevice_ = devices[chosen.index];
    vkGetPhysicalDeviceProperties(physicalDevice_, &properties_);
    deviceName_ = properties_.deviceName;
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties2.pNext = &driver;
    vkGetPhysicalDeviceProperties2(physicalDevice_, &properties2);
    driverVersion_ = std::string(driver.driverName) + " " + driver.driverInfo;
    vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
    // CPU devices and integrated GPUs have host-visible device memory, which Buffer maps instead of staging.
    discreteMemory_ = discreteMemoryWanted(options);
    mapsDeviceMemory_ = !discreteMemory_ && (properties_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ||
                                             properties_.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU);

    VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &features12;
    vkGetPhysicalDeviceFeatures2(physicalDevice_, &features);
    if (!features12.bufferDeviceAddress || !features.features.shaderInt64 || !features12.hostQueryReset)
        throw std::runtime_error("Vulkan device " + deviceName_ +
                                 " lacks bufferDeviceAddress, shaderInt64 or hostQueryReset, which Ripple needs");

    std::string limitsText;
    if (options.limits) limitsText = *options.limits;
    else if (const char* env = std::getenv("RIPPLE_VK_LIMITS")) limitsText = env;
    const std::string lowered = applyLimitsOverride(properties_.limits, parseLimitsOverride(limitsText));

    if (options.printDeviceChoice)
        std::fprintf(stderr, "ripple: Vulkan device %u of %u: %s (%s), driver %s%s%s%s\n", chosen.index, count,
                     deviceName_.c_str(), deviceTypeName(properties_.deviceType), driverVersion_.c_str(),
                     chosen.reason.empty() ? "" : ", ", chosen.reason.c_str(),
                     discreteMemory_ ? "; discrete-memory mode: device buffers are staged, never mapped" : "");
    if (options.printDeviceChoice && !lowered.empty())
        std::fprintf(stderr, "ripple: Vulkan limits lowered by %s: %s\n",
                     options.limits ? "ContextOptions::limits" : "RIPPLE_VK_LIMITS", lowered.c_str());
}

void Context::probeRayQuery(const ContextOptions& options, std::vector<const char*>& extensions) {
    uint32_t count = 0;
    RIPPLE_VK_CHECK(vkEnumerateDeviceExtensionProperties(physicalDevice_, nullptr, &count, nullptr));
    std::vector<VkExtensionProperties> available(count);
    RIPPLE_VK_CHECK(vkEnumerateDeviceExtensionProperties(physicalDevice_, nullptr, &count, available.data()));
    auto has = [&](const char* name) {
        return std::any_of(available.begin(), available.end(),
                           [&](const auto& e) { return std::strcmp(e.extensionName, name) == 0; });
    };
    const char* needed[] = {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME, VK_KHR_RAY_QUERY_EXTENSION_NAME,
                            VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};
    std::vector<std::string> missing;
    for (const char* name : needed)
        if (!has(name)) missing.emplace_back(name);
    if (missing.empty()) {
        VkPhysicalDeviceAccelerationStructureFeaturesKHR asFeatures{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
        VkPhysicalDeviceRayQueryFeaturesKHR rayQueryFeatures{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
        asFeatures.pNext = &rayQueryFeatures;
        VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        features.pNext = &asFeatures;
        vkGetPhysicalDeviceFeatures2(physicalDevice_, &features);
        if (!asFeatures.accelerationStructure) missing.emplace_back("the accelerationStructure feature");
        if (!rayQueryFeatures.rayQuery) missing.emplace_back("the rayQuery feature");
    }
    if (!options.rayQuery) missing.emplace_back("(ray queries disabled by ContextOptions::rayQuery)");
    for (const std::string& m : missing) rayQueryMissing_ += (rayQueryMissing_.empty() ? "" : ", ") + m;
    rayQuery_ = missing.empty();
    if (!rayQuery_) return;
    extensions.insert(extensions.end(), std::begin(needed), std::end(needed));

    VkPhysicalDeviceAccelerationStructurePropertiesKHR asProperties{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &asProperties;
    vkGetPhysicalDeviceProperties2(physicalDevice_, &properties);
    scratchAlignment_ = std::max<VkDeviceSize>(1, asProperties.minAccelerationStructureScratchOffsetAlignment);
}

void Context::loadAccelerationStructureFunctions() {
    auto load = [&](auto& fn, const char* name) {
        fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(vkGetDeviceProcAddr(device_, name));
        if (!fn) throw std::runtime_error(std::string("Vulkan device ") + deviceName_ + " reports ray queries but has no " + name);
    };
    load(asFunctions_.create, "vkCreateAccelerationStructureKHR");
    load(asFunctions_.destroy, "vkDestroyAccelerationStructureKHR");
    load(asFunctions_.buildSizes, "vkGetAccelerationStructureBuildSizesKHR");
    load(asFunctions_.cmdBuild, "vkCmdBuildAccelerationStructuresKHR");
    load(asFunctions_.deviceAddress, "vkGetAccelerationStructureDeviceAddressKHR");
    load(asFunctions_.cmdWriteProperties, "vkCmdWriteAccelerationStructuresPropertiesKHR");
    load(asFunctions_.cmdCopy, "vkCmdCopyAccelerationStructureKHR");
}

Context::~Context() { destroy(); }

Context::StoredPipeline Context::storedPipeline(const std::string& key,
                                                const std::function<StoredPipeline()>& build) const {
    {
        std::lock_guard lock(pipelinesMutex_);
        if (auto found = pipelines_.find(key); found != pipelines_.end()) return found->second;
    }
    const StoredPipeline built = build();  // outside the lock: threads build different kernels at once
    std::lock_guard lock(pipelinesMutex_);
    const auto [stored, inserted] = pipelines_.try_emplace(key, built);
    if (!inserted) {  // another thread built the same one meanwhile
        vkDestroyPipeline(device_, built.pipeline, nullptr);
        vkDestroyPipelineLayout(device_, built.layout, nullptr);
    }
    return stored->second;
}

size_t Context::storedPipelineCount() const {
    std::lock_guard lock(pipelinesMutex_);
    return pipelines_.size();
}

void Context::destroy() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        for (const auto& [key, stored] : pipelines_) {
            vkDestroyPipeline(device_, stored.pipeline, nullptr);
            vkDestroyPipelineLayout(device_, stored.layout, nullptr);
        }
        pipelines_.clear();
        if (pipelineCache_) vkDestroyPipelineCache(device_, pipelineCache_, nullptr);
        if (fence_) vkDestroyFence(device_, fence_, nullptr);
        if (commandPool_) vkDestroyCommandPool(device_, commandPool_, nullptr);
        vkDestroyDevice(device_, nullptr);
        device_ = VK_NULL_HANDLE;
    }
    if (messenger_) {
        auto destroyMessenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        destroyMessenger(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance_) {
        vkDestroyInstance(instance_, nullptr);
        instance_ = VK_NULL_HANDLE;
    }
}

uint32_t Context::memoryType(uint32_t typeBits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) const {
    uint32_t fallback = UINT32_MAX;
    for (uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i))) continue;
        const VkMemoryPropertyFlags flags = memoryProperties_.memoryTypes[i].propertyFlags;
        if ((flags & required) != required) continue;
        if ((flags & preferred) == preferred) return i;
        if (fallback == UINT32_MAX) fallback = i;
    }
    if (fallback == UINT32_MAX) throw std::runtime_error("no Vulkan memory type with the required properties");
    return fallback;
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
    std::lock_guard lock(submitMutex());
    VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocInfo.commandPool = commandPool_;
    allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocInfo.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    RIPPLE_VK_CHECK(vkAllocateCommandBuffers(device_, &allocInfo, &cmd));
    struct FreeOnExit {
        VkDevice device; VkCommandPool pool; VkCommandBuffer cmd;
        ~FreeOnExit() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
    } freeOnExit{device_, commandPool_, cmd};

    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    RIPPLE_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    RIPPLE_VK_CHECK(vkEndCommandBuffer(cmd));

    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    RIPPLE_VK_CHECK(vkResetFences(device_, 1, &fence_));
    RIPPLE_VK_CHECK(vkQueueSubmit(queue_, 1, &submit, fence_));
    RIPPLE_VK_CHECK(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX));
}

void Context::setName(VkObjectType type, uint64_t handle, const std::string& name) const {
    if (!setObjectName_ || !handle) return;
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name.c_str();
    setObjectName_(device_, &info);
}

}  // namespace ripple::vk
