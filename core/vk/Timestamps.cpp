// GPU timestamp queries, converted to seconds with the device's timestamp period.
#include "core/vk/Timestamps.h"

#include <algorithm>

namespace ripple::vk {

Timestamps::Timestamps(const Context& context, uint32_t capacity) : context_(context), capacity_(capacity) {
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = capacity;
    RIPPLE_VK_CHECK(vkCreateQueryPool(context.device(), &info, nullptr, &pool_));
    vkResetQueryPool(context.device(), pool_, 0, capacity_);  // hostQueryReset: usable before any submission
    context.setName(VK_OBJECT_TYPE_QUERY_POOL, reinterpret_cast<uint64_t>(pool_), "ripple timestamps");
}

Timestamps::~Timestamps() { vkDestroyQueryPool(context_.device(), pool_, nullptr); }

void Timestamps::reset(VkCommandBuffer cmd) { vkCmdResetQueryPool(cmd, pool_, 0, capacity_); }

void Timestamps::write(VkCommandBuffer cmd, uint32_t index) {
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, index);
}

double Timestamps::seconds(uint32_t from, uint32_t to) const {
    uint64_t stamps[2] = {};
    RIPPLE_VK_CHECK(vkGetQueryPoolResults(context_.device(), pool_, from, 1, sizeof(uint64_t), &stamps[0],
                                          sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    RIPPLE_VK_CHECK(vkGetQueryPoolResults(context_.device(), pool_, to, 1, sizeof(uint64_t), &stamps[1],
                                          sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    return static_cast<double>(stamps[1] - stamps[0]) * context_.properties().limits.timestampPeriod * 1e-9;
}

std::vector<double> Timestamps::read(uint32_t count) const {
    std::vector<uint64_t> stamps(std::min(count, capacity_));
    if (stamps.empty()) return {};
    RIPPLE_VK_CHECK(vkGetQueryPoolResults(context_.device(), pool_, 0, uint32_t(stamps.size()),
                                          stamps.size() * sizeof(uint64_t), stamps.data(), sizeof(uint64_t),
                                          VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    const double period = context_.properties().limits.timestampPeriod * 1e-9;
    std::vector<double> seconds(stamps.size());
    for (size_t i = 0; i < stamps.size(); ++i) seconds[i] = double(stamps[i] - stamps[0]) * period;
    return seconds;
}

}  // namespace ripple::vk
