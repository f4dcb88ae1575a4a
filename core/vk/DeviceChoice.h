// Which Vulkan device a process takes: the best kind present (discrete GPU, then integrated, virtual, CPU),
// and among the devices of that kind the one given by the process's rank on its node, so that the ranks
// of one node spread over its GPUs; an override (an index or a name substring) wins. A pure function of
// the devices' kinds and names, tested without Vulkan; and the devices as a Vulkan instance lists them.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace ripple::vk {

struct DeviceDescription {
    std::string name;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    std::string driver;  // the driver's name and version as it reports them; empty where unknown
};

// "discrete GPU", "integrated GPU", "virtual GPU", "CPU" or "other".
const char* deviceTypeName(VkPhysicalDeviceType type);

struct DeviceChoice {
    uint32_t index = 0;  // into the devices given
    // Why, for the start-up line: "" for the only device of its kind and one rank on the node; else which
    // of how many devices of the kind this node-local rank takes, or which override chose it.
    std::string reason;
};

// `localRank` of `localRanks`: this process among those of the same node (MPI_COMM_TYPE_SHARED). Without an
// override it takes the (localRank mod n)-th of the n devices of the best kind, in the order given. An
// override is a device index (all digits) or a case-insensitive substring of the name (the first device
// that matches); `overrideSource` names where it came from in the reason and errors ("RIPPLE_VK_DEVICE":
// `chosen by RIPPLE_VK_DEVICE "1"`).
// Throws std::runtime_error for no devices, an override that matches none (listing the devices), or a local
// rank not below the count.
DeviceChoice chooseDevice(std::span<const DeviceDescription> devices, uint32_t localRank, uint32_t localRanks,
                          std::string_view override, std::string_view overrideSource);

// Every physical device of `instance`, in its order.
std::vector<DeviceDescription> describeDevices(VkInstance instance);
// The same from an instance of its own (no layers), for listings made before or without a Context.
std::vector<DeviceDescription> listDevices();

}  // namespace ripple::vk
