// The device each rank of a node takes (vk::chooseDevice): the best kind present, spread over the node's
// ranks in turn; an override (index or name substring) wins. Pure: made-up device lists, no Vulkan.
#include "core/vk/DeviceChoice.h"

#include <doctest/doctest.h>

#include <stdexcept>
#include <string>
#include <vector>

using ripple::vk::chooseDevice;
using ripple::vk::DeviceDescription;

namespace {

constexpr VkPhysicalDeviceType kDiscrete = VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
constexpr VkPhysicalDeviceType kIntegrated = VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU;
constexpr VkPhysicalDeviceType kCpu = VK_PHYSICAL_DEVICE_TYPE_CPU;

// The index each of `ranks` node-local ranks takes, without an override.
std::vector<uint32_t> choices(const std::vector<DeviceDescription>& devices, uint32_t ranks) {
    std::vector<uint32_t> indices;
    for (uint32_t r = 0; r < ranks; ++r) indices.push_back(chooseDevice(devices, r, ranks, "", "RIPPLE_VK_DEVICE").index);
    return indices;
}

const std::vector<DeviceDescription> kLavapipe = {{"llvmpipe (LLVM 15.0.6, 256 bits)", kCpu, "llvmpipe"}};
const std::vector<DeviceDescription> kFourGpusAndCpu = {{"NVIDIA H100 #0", kDiscrete, ""}, {"NVIDIA H100 #1", kDiscrete, ""},
                                                        {"NVIDIA H100 #2", kDiscrete, ""}, {"NVIDIA H100 #3", kDiscrete, ""},
                                                        {"llvmpipe", kCpu, ""}};

}  // namespace

TEST_CASE("device choice: one device serves every rank of the node") {
    CHECK(choices(kLavapipe, 1) == std::vector<uint32_t>{0});
    CHECK(choices(kLavapipe, 4) == std::vector<uint32_t>{0, 0, 0, 0});
    CHECK(chooseDevice(kLavapipe, 0, 1, "", "RIPPLE_VK_DEVICE").reason.empty());  // nothing to say: the only one
    CHECK(chooseDevice(kLavapipe, 3, 4, "", "RIPPLE_VK_DEVICE").reason ==
          "node-local rank 3 of 4 takes CPU 0 of 1 (ranks share devices: more ranks than devices of this kind on the node)");
}

TEST_CASE("device choice: four discrete GPUs and a CPU device, four ranks: one GPU each, never the CPU") {
    CHECK(choices(kFourGpusAndCpu, 4) == std::vector<uint32_t>{0, 1, 2, 3});
    CHECK(chooseDevice(kFourGpusAndCpu, 2, 4, "", "RIPPLE_VK_DEVICE").reason ==
          "node-local rank 2 of 4 takes discrete GPU 2 of 4");
    // The CPU device listed first changes the indices, not the GPUs taken.
    std::vector<DeviceDescription> cpuFirst = {kFourGpusAndCpu[4]};
    cpuFirst.insert(cpuFirst.end(), kFourGpusAndCpu.begin(), kFourGpusAndCpu.begin() + 4);
    CHECK(choices(cpuFirst, 4) == std::vector<uint32_t>{1, 2, 3, 4});
    // One rank alone on the node takes the first GPU.
    CHECK(choices(kFourGpusAndCpu, 1) == std::vector<uint32_t>{0});
}

TEST_CASE("device choice: more ranks than GPUs take them in turn") {
    const std::vector<DeviceDescription> two = {{"GPU A", kDiscrete, ""}, {"GPU B", kDiscrete, ""}};
    CHECK(choices(two, 4) == std::vector<uint32_t>{0, 1, 0, 1});
    CHECK(choices(two, 3) == std::vector<uint32_t>{0, 1, 0});
    // Only the best kind counts: an integrated GPU beside one discrete GPU is not used.
    const std::vector<DeviceDescription> mixed = {{"iGPU", kIntegrated, ""}, {"dGPU", kDiscrete, ""}, {"cpu", kCpu, ""}};
    CHECK(choices(mixed, 3) == std::vector<uint32_t>{1, 1, 1});
    const std::vector<DeviceDescription> noDiscrete = {{"cpu", kCpu, ""}, {"iGPU 0", kIntegrated, ""},
                                                       {"iGPU 1", kIntegrated, ""}};
    CHECK(choices(noDiscrete, 2) == std::vector<uint32_t>{1, 2});
}

TEST_CASE("device choice: an override wins over the rank, by index or name; a bad one names the devices") {
    for (uint32_t rank = 0; rank < 4; ++rank) {
        CHECK(chooseDevice(kFourGpusAndCpu, rank, 4, "4", "RIPPLE_VK_DEVICE").index == 4);
        CHECK(chooseDevice(kFourGpusAndCpu, rank, 4, "LLVMPIPE", "RIPPLE_VK_DEVICE").index == 4);
        CHECK(chooseDevice(kFourGpusAndCpu, rank, 4, "h100 #2", "RIPPLE_VK_DEVICE").index == 2);
    }
    CHECK(chooseDevice(kFourGpusAndCpu, 1, 4, "4", "RIPPLE_VK_DEVICE").reason == "chosen by RIPPLE_VK_DEVICE \"4\"");
    CHECK(chooseDevice(kFourGpusAndCpu, 0, 1, "h100", "the device parameter vulkanDevice").index == 0);  // the first match
    CHECK_THROWS_WITH_AS(chooseDevice(kFourGpusAndCpu, 0, 1, "7", "RIPPLE_VK_DEVICE"),
                         doctest::Contains("RIPPLE_VK_DEVICE \"7\" matches no Vulkan device; devices are:\n  0: NVIDIA H100 #0"),
                         std::runtime_error);
    CHECK_THROWS_WITH_AS(chooseDevice(kFourGpusAndCpu, 0, 1, "radeon", "the device parameter vulkanDevice"),
                         doctest::Contains("the device parameter vulkanDevice \"radeon\" matches no Vulkan device"),
                         std::runtime_error);
    CHECK_THROWS_AS(chooseDevice({}, 0, 1, "", "RIPPLE_VK_DEVICE"), std::runtime_error);
    CHECK_THROWS_AS(chooseDevice(kLavapipe, 4, 4, "", "RIPPLE_VK_DEVICE"), std::runtime_error);
}
