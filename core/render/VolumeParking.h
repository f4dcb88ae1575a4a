// Resume rounds for volume marches (pt_volume, pt_shadow_volume). Each invocation of a volume stage takes
// at most `stepBudget` tracking steps; a march that spends them is parked in a pool with what it found so
// far (shared/volume.h: VolumeParked) and continued by the next round, an indirect dispatch the kernels
// size themselves, so the host never reads a count. A march still unfinished after the last round is
// flagged (its record HIT_FLAG_RAN_OUT, or a shadow ray that adds nothing), never given a wrong answer.
// The pools grow with the largest batch seen and exist only once a frame has volumes.
#pragma once

#include "core/vk/Buffer.h"
#include "core/vk/ComputePipeline.h"
#include "shaders/shared/path.h"
#include "shaders/shared/volume.h"

#include <cstdint>

namespace ripple::core {

// Steps an invocation may take: every step makes progress (a tentative collision or a macrocell crossed);
// at most what the kernels' nested loops allow.
inline constexpr uint32_t kMinVolumeStepBudget = 1;
inline constexpr uint32_t kMaxVolumeStepBudget = 32768u * 32u;  // VOLUME_STEP_CHUNK * VOLUME_STEP_CHUNKS

struct VolumeParkingOptions {
    // About a million steps per march in all (a ray through a macrocell of extinction 1e6 takes about as
    // many null collisions per unit), in rounds of 2^17: on a GPU no invocation runs for long.
    uint32_t stepBudget = 1u << 17;
    uint32_t resumeRounds = 7;  // at most gpu::VOLUME_MAX_RESUME_ROUNDS
};

class VolumeParking {
public:
    // Throws std::invalid_argument for a budget or round count out of range.
    VolumeParking(const vk::Context& context, const VolumeParkingOptions& options);

    // Records `stage` over its items with `p` (count, countSource and the rest already set; the first
    // dispatch is direct with `count` items when `indirect` is null, else indirect from that buffer and
    // offset), then its resume rounds. `capacity`: the most items the stage can have; callers keep it within
    // one dispatch (maxComputeWorkGroupCount workgroups), since the rounds' workgroups are counted by the
    // kernels from the marches parked, at most the stage's items.
    struct Launch {
        uint32_t count = 0;
        const vk::Buffer* indirect = nullptr;
        VkDeviceSize indirectOffset = 0;
        uint32_t workgroupSize = 64;
    };
    void run(VkCommandBuffer cmd, const vk::ComputePipeline& stage, gpu::StageParams p, uint32_t capacity,
             const Launch& launch);

private:
    void reserve(uint32_t capacity);

    const vk::Context& context_;
    VolumeParkingOptions options_;
    uint32_t capacity_ = 0;
    vk::Buffer pools_;  // VolumeParkingHeader, then 2 * capacity_ VolumeParked
};

}  // namespace ripple::core
