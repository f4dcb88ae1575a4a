// The device choice per node-local rank, and the devices a Vulkan instance lists (see DeviceChoice.h).
#include "core/vk/DeviceChoice.h"

#include "core/vk/Check.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace ripple::vk {

namespace {

// Lower is better: discrete GPU, then integrated, then virtual, then CPU (lavapipe).
int typeRank(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
    }
}

std::string lowercase(std::string_view s) {
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

}  // namespace

const char* deviceTypeName(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
    }
}

DeviceChoice chooseDevice(std::span<const DeviceDescription> devices, uint32_t localRank, uint32_t localRanks,
                          std::string_view override, std::string_view overrideSource) {
    if (devices.empty())
        throw std::runtime_error("no Vulkan device found (for a CPU device install mesa-vulkan-drivers: lavapipe)");
    if (localRanks == 0 || localRank >= localRanks)
        throw std::runtime_error("node-local rank " + std::to_string(localRank) + " of " + std::to_string(localRanks) +
                                 " is not a rank of the node");
    if (!override.empty()) {
        const bool numeric = std::all_of(override.begin(), override.end(), [](unsigned char c) { return std::isdigit(c); });
        for (uint32_t i = 0; i < devices.size(); ++i)
            if (numeric ? std::to_string(i) == override
                        : lowercase(devices[i].name).find(lowercase(override)) != std::string::npos)
                return {i, "chosen by " + std::string(overrideSource) + " \"" + std::string(override) + "\""};
        std::string names;
        for (uint32_t i = 0; i < devices.size(); ++i) names += "\n  " + std::to_string(i) + ": " + devices[i].name;
        throw std::runtime_error(std::string(overrideSource) + " \"" + std::string(override) +
                                 "\" matches no Vulkan device; devices are:" + names);
    }
    int best = typeRank(devices[0].type);
    for (const DeviceDescription& d : devices) best = std::min(best, typeRank(d.type));
    std::vector<uint32_t> candidates;
    for (uint32_t i = 0; i < devices.size(); ++i)
        if (typeRank(devices[i].type) == best) candidates.push_back(i);
    const auto n = static_cast<uint32_t>(candidates.size());
    const uint32_t k = localRank % n;
    DeviceChoice choice{candidates[k], {}};
    if (n > 1 || localRanks > 1) {
        const std::string kind = deviceTypeName(devices[candidates[k]].type);
        choice.reason = "node-local rank " + std::to_string(localRank) + " of " + std::to_string(localRanks) + " takes " +
                        kind + " " + std::to_string(k) + " of " + std::to_string(n);
        if (localRanks > n) choice.reason += " (ranks share devices: more ranks than devices of this kind on the node)";
    }
    return choice;
}

std::vector<DeviceDescription> describeDevices(VkInstance instance) {
    uint32_t count = 0;
    RIPPLE_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> handles(count);
    RIPPLE_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, handles.data()));
    std::vector<DeviceDescription> devices;
    for (VkPhysicalDevice handle : handles) {
        VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
        VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
        properties.pNext = &driver;
        vkGetPhysicalDeviceProperties2(handle, &properties);
        devices.push_back({properties.properties.deviceName, properties.properties.deviceType,
                           std::string(driver.driverName) + " " + driver.driverInfo});
    }
    return devices;
}

std::vector<DeviceDescription> listDevices() {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "ripple";
    app.pEngineName = "ripple";
    app.apiVersion = VK_API_VERSION_1_2;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    VkInstance instance = VK_NULL_HANDLE;
    RIPPLE_VK_CHECK(vkCreateInstance(&info, nullptr, &instance));
    try {
        std::vector<DeviceDescription> devices = describeDevices(instance);
        vkDestroyInstance(instance, nullptr);
        return devices;
    } catch (...) {
        vkDestroyInstance(instance, nullptr);
        throw;
    }
}

}  // namespace ripple::vk
