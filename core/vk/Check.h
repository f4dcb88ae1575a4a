// The one way Vulkan calls are checked: RIPPLE_VK_CHECK(call) throws VulkanError naming the call, the
// VkResult and the source line.
#pragma once

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace ripple::vk {

const char* resultName(VkResult result);

class VulkanError : public std::runtime_error {
public:
    VulkanError(const std::string& what, VkResult result) : std::runtime_error(what), result_(result) {}
    VkResult result() const { return result_; }

private:
    VkResult result_;
};

[[noreturn]] void throwVulkanError(const char* call, VkResult result, const char* file, int line);

}  // namespace ripple::vk

#define RIPPLE_VK_CHECK(call)                                                           \
    do {                                                                                \
        const VkResult ripple_vk_result_ = (call);                                      \
        if (ripple_vk_result_ != VK_SUCCESS)                                            \
            ::ripple::vk::throwVulkanError(#call, ripple_vk_result_, __FILE__, __LINE__); \
    } while (0)
