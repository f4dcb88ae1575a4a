// Where a frame's GPU time goes: a timestamp after each stage of the wavefront loop (a few dozen a frame),
// the time since the previous stamp charged to that stage. PathTracer::render returns the sums in
// FrameStats; the ANARI frame reports them (ripple.stageMicroseconds.NAME) and ripple-render --stats prints
// them.
#pragma once

#include "core/vk/Timestamps.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ripple::core {

enum class Stage : uint32_t {
    Generate,       // camera rays
    TraceClosest,   // closest hits of the path rays
    Surface,        // the surface record at each hit
    Volume,         // free flight through volumes
    Channels,       // depth, normal, albedo and id channels at the first hits
    Shade,          // emission, next-event estimation, the next direction
    TraceAny,       // occlusion of the shadow rays
    ShadowVolume,   // transmittance of volumes along shadow rays
    ShadowResolve,  // the shadow rays' contributions
    QueueAdvance,   // queue lengths for the next bounce
    Accumulate,     // the sample into the accumulation
    Count
};
inline constexpr size_t kStageCount = size_t(Stage::Count);
using StageSeconds = std::array<double, kStageCount>;

// "generate", "traceClosest", ...: the names the frame properties use.
const char* stageName(Stage stage);

class StageProfile {
public:
    explicit StageProfile(const vk::Context& context, uint32_t capacity = 1024);

    // Starts a submission's stamps (call first in its command buffer).
    void begin(VkCommandBuffer cmd);
    // Stamps the end of `stage` (dropped once the submission holds `capacity` stamps).
    void mark(VkCommandBuffer cmd, Stage stage);
    // After the submission finished: adds each stage's time to `seconds`.
    void collect(StageSeconds& seconds);

private:
    vk::Timestamps stamps_;
    std::vector<Stage> stages_;  // stamp i + 1 ends stages_[i]
};

}  // namespace ripple::core
