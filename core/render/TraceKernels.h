// Host side of the closest-hit and any-hit traversal kernels (shaders/trace_closest.comp,
// trace_any.comp). A ray whose traversal spends its step budget is parked in a resume pool and continued
// by further indirect dispatches; a ray still unfinished after the last round is flagged
// HIT_FLAG_RAN_OUT, never silently wrong. With TraceOptions::traversal resolving to RayQuery the same
// calls run the ray-query kernels instead (RayQueryTraversal.h), on scenes built for them.
#pragma once

#include "core/render/FeatureSet.h"
#include "core/render/RayQueryTraversal.h"
#include "core/render/Traversal.h"
#include "core/scene/Scene.h"
#include "core/vk/Buffer.h"
#include "core/vk/ComputePipeline.h"
#include "shaders/shared/ray.h"

#include <memory>
#include <span>
#include <vector>

namespace ripple::core {

// Every loop iteration of a trace invocation counts against its step budget. The least budget that still
// makes progress covers the copies of a full stack in and out of the resume pool and a few steps. The most
// stays under lavapipe's silent loop cap: its limiter starts at 65,535 but, measured on Mesa 22.3, ends the
// traversal loop after 32,768 iterations (two decrements per iteration), with no error of any kind.
inline constexpr uint32_t kMinStepBudget = 2 * gpu::TRAVERSAL_STACK_SIZE + 8;
inline constexpr uint32_t kMaxStepBudget = 32000;

struct TraceOptions {
    uint32_t workgroupSize = 64;
    // Node visits plus primitive tests per invocation before it parks its state (see kMaxStepBudget).
    uint32_t stepBudget = 30000;
    uint32_t resumeRounds = 4;          // extra dispatches for parked traversals
    uint32_t resumeCapacity = 1u << 14; // parked traversals per round; overflow is flagged RAN_OUT
    Traversal traversal = Traversal::Auto;  // resolved at construction (Traversal.h); see traversal()
};

// A ray count that a kernel wrote on the device: the trace reads it there and is launched with
// vkCmdDispatchIndirect, so the host never waits to learn it.
struct DeviceRayCount {
    const vk::Buffer* buffer = nullptr;  // holds both, made with VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT
    VkDeviceSize countOffset = 0;        // the uint ray count
    VkDeviceSize groupsOffset = 0;       // VkDispatchIndirectCommand for workgroups of options().workgroupSize
};

class TraceKernels {
public:
    TraceKernels(const vk::Context& context, const TraceOptions& options = {});

    // Device-side batch: rays and results already in GPU buffers (the wavefront path tracer's use).
    void traceClosest(VkCommandBuffer cmd, const Scene& scene, const vk::Buffer& rays, const vk::Buffer& hits,
                      uint32_t rayCount);
    void traceAny(VkCommandBuffer cmd, const Scene& scene, const vk::Buffer& rays, const vk::Buffer& occluded,
                  uint32_t rayCount);
    // The same with the count on the device; at most one dispatch's worth of rays (maxComputeWorkGroupCount).
    void traceClosest(VkCommandBuffer cmd, const Scene& scene, const vk::Buffer& rays, const vk::Buffer& hits,
                      const DeviceRayCount& count);
    void traceAny(VkCommandBuffer cmd, const Scene& scene, const vk::Buffer& rays, const vk::Buffer& occluded,
                  const DeviceRayCount& count);

    // Host convenience for tests and benchmarks: upload, trace, wait, download.
    std::vector<gpu::Hit> traceClosest(const Scene& scene, std::span<const gpu::Ray> rays);
    // One uint per ray: HIT_MISS or HIT_FOUND in the low byte, HIT_FLAG_* above.
    std::vector<uint32_t> traceAny(const Scene& scene, std::span<const gpu::Ray> rays);

    const TraceOptions& options() const { return options_; }
    // The back-end in use: Software or RayQuery (options().traversal resolved on this device).
    Traversal traversal() const { return traversal_; }

    // Specialises the kernels for the geometry kinds in `features` (FEATURE_*; other bits are ignored):
    // later traces run the variant without the tests of absent kinds. Every kind by default. A scene
    // holding a kind the features leave out traces those primitives as misses.
    void useFeatures(uint32_t features);
    const PipelineCache& pipelines() const { return pipelines_; }

private:
    void dispatch(VkCommandBuffer cmd, vk::ComputePipeline& pipeline, const Scene& scene, const vk::Buffer& rays,
                  const vk::Buffer& results, uint32_t rayCount, const DeviceRayCount* deviceCount = nullptr);
    void resumeRounds(VkCommandBuffer cmd, vk::ComputePipeline& pipeline, gpu::TraceParams params);
    template <class Result>
    std::vector<Result> traceOnHost(vk::ComputePipeline& pipeline, const Scene& scene, std::span<const gpu::Ray> rays);
    void ensureResumePools();

    const vk::Context& context_;
    TraceOptions options_;
    vk::ComputePipeline closest_;  // software traversal; built by useFeatures
    vk::ComputePipeline any_;
    bool featuresChosen_ = false;  // useFeatures has run (the first trace runs it for every feature if not)
    PipelineCache pipelines_;
    vk::Buffer resumePools_[2];
    Traversal traversal_ = Traversal::Software;
    std::unique_ptr<RayQueryTraversal> rayQuery_;  // RayQuery only
};

}  // namespace ripple::core
