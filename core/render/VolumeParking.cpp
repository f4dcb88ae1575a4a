// Host side of the volume stages' resume rounds (VolumeParking.h).
#include "core/render/VolumeParking.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ripple::core {

VolumeParking::VolumeParking(const vk::Context& context, const VolumeParkingOptions& options)
    : context_(context), options_(options) {
    if (options_.stepBudget < kMinVolumeStepBudget || options_.stepBudget > kMaxVolumeStepBudget)
        throw std::invalid_argument("VolumeParkingOptions::stepBudget must be in [" + std::to_string(kMinVolumeStepBudget) +
                                    ", " + std::to_string(kMaxVolumeStepBudget) + "], not " +
                                    std::to_string(options_.stepBudget));
    if (options_.resumeRounds > gpu::VOLUME_MAX_RESUME_ROUNDS)
        throw std::invalid_argument("VolumeParkingOptions::resumeRounds must be at most " +
                                    std::to_string(gpu::VOLUME_MAX_RESUME_ROUNDS) + ", not " +
                                    std::to_string(options_.resumeRounds));
}

void VolumeParking::reserve(uint32_t capacity) {
    if (pools_ && capacity <= capacity_) return;
    capacity_ = std::max(capacity, capacity_ * 2);
    const VkDeviceSize bytes = sizeof(gpu::VolumeParkingHeader) + 2 * VkDeviceSize(capacity_) * sizeof(gpu::VolumeParked);
    pools_ = vk::Buffer(context_, bytes, "volume parking pools", VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
}

void VolumeParking::run(VkCommandBuffer cmd, const vk::ComputePipeline& stage, gpu::StageParams p, uint32_t capacity,
                        const Launch& launch) {
    if (launch.count == 0 && !launch.indirect) return;
    // Without resume rounds only the header is needed: it still sets the budget (and nothing parks).
    const bool parks = options_.resumeRounds > 0;
    reserve(parks ? std::max(capacity, 1u) : 0);
    gpu::VolumeParkingHeader header{};
    for (gpu::ResumeHeader& round : header.parked) round = {0, 0, 1, 1};
    header.capacity = capacity_;
    header.stepBudget = options_.stepBudget;
    header.lastRound = options_.resumeRounds;
    // The previous volume stage in this command buffer may still read the header (its last round's
    // indirect dispatch and counts): finish with it before rewriting it.
    vk::computeBarrier(cmd);
    vkCmdUpdateBuffer(cmd, pools_.handle(), 0, sizeof(header), &header);
    p.volumeParking = pools_.address();
    p.resumeRound = 0;
    vk::computeBarrier(cmd);
    stage.bind(cmd);
    stage.pushConstants(cmd, &p, sizeof(p));
    if (launch.indirect) vkCmdDispatchIndirect(cmd, launch.indirect->handle(), launch.indirectOffset);
    else stage.dispatch(cmd, (launch.count + launch.workgroupSize - 1) / launch.workgroupSize);
    for (uint32_t round = 1; parks && round <= options_.resumeRounds; ++round) {
        vk::computeBarrier(cmd);
        p.resumeRound = round;
        stage.pushConstants(cmd, &p, sizeof(p));
        vkCmdDispatchIndirect(cmd, pools_.handle(),
                              (round - 1) * sizeof(gpu::ResumeHeader) + offsetof(gpu::ResumeHeader, groupsX));
    }
}

}  // namespace ripple::core
