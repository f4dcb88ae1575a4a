// Host side of the ray-query trace kernels (shaders/trace_closest_rq.comp, trace_any_rq.comp): the
// back-end TraceKernels uses when its traversal resolves to Traversal::RayQuery. No step budget and no
// resume rounds: the device traverses; a ray it could not finish is flagged HIT_FLAG_RAN_OUT.
#pragma once

#include "core/render/FeatureSet.h"
#include "core/scene/Scene.h"
#include "core/vk/ComputePipeline.h"

namespace ripple::core {

// One trace launch: rays and results by address, the count given or read on the device.
struct RayQueryLaunch {
    bool anyHit = false;
    VkDeviceAddress rays = 0;
    VkDeviceAddress results = 0;          // Hit[] (closest) or uint[] (any-hit)
    uint32_t rayCount = 0;                // used when rayCountAddress is 0
    VkDeviceAddress rayCountAddress = 0;  // nonzero: the count is the uint there; dispatched indirectly from
    VkBuffer indirectBuffer = VK_NULL_HANDLE;  // a VkDispatchIndirectCommand here
    VkDeviceSize indirectOffset = 0;
};

class RayQueryTraversal {
public:
    // Throws std::runtime_error when the device lacks ray queries.
    RayQueryTraversal(const vk::Context& context, uint32_t workgroupSize);

    // Records the launch into `cmd`. The scene must have been built for ray-query traversal.
    void dispatch(VkCommandBuffer cmd, const Scene& scene, const RayQueryLaunch& launch);
    // As TraceKernels::useFeatures: only the sphere, cylinder and cone confirmations are specialised.
    void useFeatures(uint32_t features, PipelineCache& cache);

private:
    const vk::Context& context_;
    uint32_t workgroupSize_;
    vk::ComputePipeline closest_;  // built by useFeatures, which must run before dispatch
    vk::ComputePipeline any_;
};

}  // namespace ripple::core
