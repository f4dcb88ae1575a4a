// A compute pipeline from embedded SPIR-V: push constants only (every buffer is reached by device
// address, so there are no descriptor sets), specialization constants for compile-time knobs. The context
// owns it (Context::storedPipeline): built on the first request for the same SPIR-V and constants on a
// device, kept until the device goes, and shared by every ComputePipeline that asks for it afterwards.
// Push constants and direct dispatches are checked against the device's limits (Context::properties()).
#pragma once

#include "core/vk/Context.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ripple::vk {

struct SpecializationConstant {
    uint32_t id;
    uint32_t value;
};

class ComputePipeline {
public:
    ComputePipeline() = default;
    // Throws std::runtime_error naming the kernel when pushConstantBytes exceeds the device's
    // maxPushConstantsSize.
    ComputePipeline(const Context& context, std::span<const uint32_t> spirv, const std::string& name,
                    uint32_t pushConstantBytes, std::span<const SpecializationConstant> constants = {});
    ComputePipeline(ComputePipeline&& other) noexcept;
    ComputePipeline& operator=(ComputePipeline&& other) noexcept;
    ComputePipeline(const ComputePipeline&) = delete;
    ComputePipeline& operator=(const ComputePipeline&) = delete;

    VkPipeline handle() const { return pipeline_; }
    VkPipelineLayout layout() const { return layout_; }
    const std::string& name() const { return name_; }

    void bind(VkCommandBuffer cmd) const;
    void pushConstants(VkCommandBuffer cmd, const void* data, uint32_t bytes) const;
    // vkCmdDispatch of `groups` workgroups along x. Work beyond the device's maxComputeWorkGroupCount[0]
    // must be split by the caller: more groups than that throw std::logic_error naming the kernel.
    void dispatch(VkCommandBuffer cmd, uint64_t groups) const;

private:
    static Context::StoredPipeline build(const Context& context, std::span<const uint32_t> spirv,
                                         const std::string& name, uint32_t pushConstantBytes,
                                         std::span<const SpecializationConstant> constants);

    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    std::string name_;
    uint32_t maxGroups_ = 0;  // the device's maxComputeWorkGroupCount[0]
};

// Barrier between dependent compute dispatches (and transfers) on the one queue.
void computeBarrier(VkCommandBuffer cmd);

}  // namespace ripple::vk
