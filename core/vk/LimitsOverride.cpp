// Parsing and applying RIPPLE_VK_LIMITS (see LimitsOverride.h).
#include "core/vk/LimitsOverride.h"

#include <algorithm>
#include <charconv>
#include <stdexcept>

namespace ripple::vk {

namespace {

std::string_view trimmed(std::string_view s) {
    while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
    while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
    return s;
}

// Lowers `value` to `wanted`; describes the change.
void lower(uint32_t& value, std::optional<uint32_t> wanted, const char* name, std::string& changes) {
    if (!wanted || *wanted >= value) return;
    changes += (changes.empty() ? "" : ", ") + std::string(name) + " " + std::to_string(*wanted) + " (device " +
               std::to_string(value) + ")";
    value = *wanted;
}

}  // namespace

LimitsOverride parseLimitsOverride(std::string_view text) {
    LimitsOverride result;
    while (!text.empty()) {
        const size_t comma = text.find(',');
        const std::string_view item = trimmed(text.substr(0, comma));
        text = comma == std::string_view::npos ? std::string_view() : text.substr(comma + 1);
        if (item.empty()) continue;
        const auto fail = [&](const std::string& why) {
            throw std::invalid_argument("RIPPLE_VK_LIMITS item '" + std::string(item) + "': " + why);
        };
        const size_t equals = item.find('=');
        if (equals == std::string_view::npos) fail("not key=value");
        const std::string_view key = trimmed(item.substr(0, equals));
        const std::string_view value = trimmed(item.substr(equals + 1));
        uint32_t number = 0;
        const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), number);
        if (value.empty() || error != std::errc() || end != value.data() + value.size() || number == 0)
            fail("the value must be a positive integer below 2^32");
        std::optional<uint32_t>* slot = key == "maxComputeWorkGroupCount" ? &result.maxComputeWorkGroupCount
                                        : key == "maxPushConstantsSize"   ? &result.maxPushConstantsSize
                                                                          : nullptr;
        if (!slot) fail(std::string("unknown limit; known: ") + kLimitsOverrideKeys);
        if (*slot) fail("given twice");
        *slot = number;
    }
    return result;
}

std::string applyLimitsOverride(VkPhysicalDeviceLimits& limits, const LimitsOverride& override) {
    std::string changes;
    for (uint32_t& count : limits.maxComputeWorkGroupCount) {
        std::string change;
        lower(count, override.maxComputeWorkGroupCount, "maxComputeWorkGroupCount", change);
        if (&count == &limits.maxComputeWorkGroupCount[0]) changes += change;  // named once for the three
    }
    lower(limits.maxPushConstantsSize, override.maxPushConstantsSize, "maxPushConstantsSize", changes);
    return changes;
}

}  // namespace ripple::vk
