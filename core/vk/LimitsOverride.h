// RIPPLE_VK_LIMITS: a debug override that lowers the limits a Vulkan device reports, so that the code paths
// which split work to fit them (dispatches larger than maxComputeWorkGroupCount, push constants against
// maxPushConstantsSize) run on a device whose own limits are generous (lavapipe: 65,535 workgroups).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace ripple::vk {

// The limits Ripple consults, each lowered where given. Buffers are reached by device address, never
// through descriptors, so maxStorageBufferRange binds nothing and is not among them.
struct LimitsOverride {
    std::optional<uint32_t> maxComputeWorkGroupCount;  // all three dimensions
    std::optional<uint32_t> maxPushConstantsSize;
    bool empty() const { return !maxComputeWorkGroupCount && !maxPushConstantsSize; }
};

inline constexpr const char* kLimitsOverrideKeys = "maxComputeWorkGroupCount, maxPushConstantsSize";

// Parses "key=value,key=value" (values positive decimal integers below 2^32; spaces around items allowed).
// Throws std::invalid_argument naming the item for an unknown key, a bad value or a repeated key.
LimitsOverride parseLimitsOverride(std::string_view text);

// Lowers `limits` to the override's values; a value above the device's leaves the device's. Returns what
// changed ("maxComputeWorkGroupCount 8 (device 65535)", comma-separated), empty when nothing did.
std::string applyLimitsOverride(VkPhysicalDeviceLimits& limits, const LimitsOverride& override);

}  // namespace ripple::vk
