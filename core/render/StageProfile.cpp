// Per-stage GPU time of the path tracer (see StageProfile.h).
#include "core/render/StageProfile.h"

namespace ripple::core {

const char* stageName(Stage stage) {
    static const char* const names[kStageCount] = {"generate", "traceClosest", "surface",       "volume",
                                                   "channels", "shade",        "traceAny",      "shadowVolume",
                                                   "shadowResolve", "queueAdvance", "accumulate"};
    return size_t(stage) < kStageCount ? names[size_t(stage)] : "unknown";
}

StageProfile::StageProfile(const vk::Context& context, uint32_t capacity) : stamps_(context, capacity) {}

void StageProfile::begin(VkCommandBuffer cmd) {
    stages_.clear();
    stamps_.reset(cmd);
    stamps_.write(cmd, 0);
}

void StageProfile::mark(VkCommandBuffer cmd, Stage stage) {
    if (stages_.size() + 1 >= stamps_.capacity()) return;
    stamps_.write(cmd, uint32_t(stages_.size() + 1));
    stages_.push_back(stage);
}

void StageProfile::collect(StageSeconds& seconds) {
    const std::vector<double> times = stamps_.read(uint32_t(stages_.size() + 1));
    for (size_t i = 0; i + 1 < times.size(); ++i) seconds[size_t(stages_[i])] += times[i + 1] - times[i];
    stages_.clear();
}

}  // namespace ripple::core
