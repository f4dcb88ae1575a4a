// Compute pipelines from embedded SPIR-V, with push constants and specialization constants, built once per
// device (Context::storedPipeline).
#include "core/vk/ComputePipeline.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace ripple::vk {

namespace {

// The key of a pipeline among the context's stored ones: its name, push constant size, specialization
// constants, and the SPIR-V's length and 64-bit FNV-1a hash (two different kernels of the same name and
// length would have to collide in 64 bits; hashing 190 KB of SPIR-V takes well under a millisecond).
std::string pipelineKey(std::span<const uint32_t> spirv, const std::string& name, uint32_t pushConstantBytes,
                        std::span<const SpecializationConstant> constants) {
    uint64_t hash = 14695981039346656037ull;
    for (const uint32_t word : spirv) hash = (hash ^ word) * 1099511628211ull;
    std::string key = name + " push " + std::to_string(pushConstantBytes) + " spirv " + std::to_string(spirv.size()) +
                      " " + std::to_string(hash);
    for (const auto& c : constants) {
        key += ' ';
        key += std::to_string(c.id);
        key += '=';
        key += std::to_string(c.value);
    }
    return key;
}

}  // namespace

ComputePipeline::ComputePipeline(const Context& context, std::span<const uint32_t> spirv, const std::string& name,
                                 uint32_t pushConstantBytes, std::span<const SpecializationConstant> constants)
    : name_(name), maxGroups_(context.properties().limits.maxComputeWorkGroupCount[0]) {
    const uint32_t maxPushBytes = context.properties().limits.maxPushConstantsSize;
    if (pushConstantBytes > maxPushBytes)
        throw std::runtime_error("kernel '" + name + "' takes " + std::to_string(pushConstantBytes) +
                                 " bytes of push constants, but Vulkan device " + context.deviceName() + " allows " +
                                 std::to_string(maxPushBytes) + " (maxPushConstantsSize)");
    const Context::StoredPipeline stored =
        context.storedPipeline(pipelineKey(spirv, name, pushConstantBytes, constants), [&] {
            return build(context, spirv, name, pushConstantBytes, constants);
        });
    pipeline_ = stored.pipeline;
    layout_ = stored.layout;
}

Context::StoredPipeline ComputePipeline::build(const Context& context, std::span<const uint32_t> spirv,
                                               const std::string& name, uint32_t pushConstantBytes,
                                               std::span<const SpecializationConstant> constants) {
    Context::StoredPipeline built;
    const VkDevice device = context.device();
    VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    moduleInfo.codeSize = spirv.size_bytes();
    moduleInfo.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    RIPPLE_VK_CHECK(vkCreateShaderModule(device, &moduleInfo, nullptr, &module));

    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.pushConstantRangeCount = pushConstantBytes > 0 ? 1 : 0;
    layoutInfo.pPushConstantRanges = &range;
    const VkResult layoutResult = vkCreatePipelineLayout(device, &layoutInfo, nullptr, &built.layout);
    if (layoutResult != VK_SUCCESS) {
        vkDestroyShaderModule(device, module, nullptr);
        throwVulkanError("vkCreatePipelineLayout", layoutResult, __FILE__, __LINE__);
    }

    std::vector<VkSpecializationMapEntry> entries;
    std::vector<uint32_t> values;
    for (const auto& c : constants) {
        entries.push_back({c.id, static_cast<uint32_t>(values.size() * sizeof(uint32_t)), sizeof(uint32_t)});
        values.push_back(c.value);
    }
    VkSpecializationInfo specialization{static_cast<uint32_t>(entries.size()), entries.data(),
                                        values.size() * sizeof(uint32_t), values.data()};

    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = entries.empty() ? nullptr : &specialization;
    info.layout = built.layout;
    const VkResult result = vkCreateComputePipelines(device, context.pipelineCache(), 1, &info, nullptr, &built.pipeline);
    vkDestroyShaderModule(device, module, nullptr);
    if (result != VK_SUCCESS) {
        vkDestroyPipelineLayout(device, built.layout, nullptr);
        throw VulkanError("creating compute pipeline '" + name + "': vkCreateComputePipelines returned " +
                              resultName(result), result);
    }
    context.setName(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(built.pipeline), name);
    context.setName(VK_OBJECT_TYPE_PIPELINE_LAYOUT, reinterpret_cast<uint64_t>(built.layout), name + " layout");
    return built;
}

ComputePipeline::ComputePipeline(ComputePipeline&& other) noexcept { *this = std::move(other); }

ComputePipeline& ComputePipeline::operator=(ComputePipeline&& other) noexcept {
    if (this != &other) {
        pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
        layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
        name_ = std::move(other.name_);
        maxGroups_ = other.maxGroups_;
    }
    return *this;
}

void ComputePipeline::bind(VkCommandBuffer cmd) const { vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_); }

void ComputePipeline::pushConstants(VkCommandBuffer cmd, const void* data, uint32_t bytes) const {
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, bytes, data);
}

void ComputePipeline::dispatch(VkCommandBuffer cmd, uint64_t groups) const {
    if (groups > maxGroups_)
        throw std::logic_error("kernel '" + name_ + "': a dispatch of " + std::to_string(groups) +
                               " workgroups exceeds the device's maxComputeWorkGroupCount of " +
                               std::to_string(maxGroups_) + " (the caller must split it)");
    vkCmdDispatch(cmd, static_cast<uint32_t>(groups), 1, 1);
}

void computeBarrier(VkCommandBuffer cmd) {
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT |
                            VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                             VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                         0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace ripple::vk
