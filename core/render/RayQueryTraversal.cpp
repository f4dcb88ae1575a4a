// Ray-query trace launches: push constants as the software kernels take them (gpu::TraceParams, resume
// fields unused), in chunks within the device's workgroup-count limit or one indirect dispatch.
#include "core/render/RayQueryTraversal.h"

#include "shaders/shared/ray.h"
#include "shaders/trace_any_rq.spv.h"
#include "shaders/trace_closest_rq.spv.h"

#include <algorithm>
#include <stdexcept>

namespace ripple::core {

RayQueryTraversal::RayQueryTraversal(const vk::Context& context, uint32_t workgroupSize)
    : context_(context), workgroupSize_(workgroupSize) {
    if (!context.supportsRayQuery())
        throw std::runtime_error("ray-query traversal needs a Vulkan device with ray queries; " + context.deviceName() +
                                 " lacks " + context.rayQueryMissing());
}

void RayQueryTraversal::useFeatures(uint32_t features, PipelineCache& cache) {
    const auto bytes = static_cast<uint32_t>(sizeof(gpu::TraceParams));
    cache.select({shaders::trace_closest_rq, "trace_closest_rq", bytes, workgroupSize_, gpu::FEATURE_GEOMETRY}, features,
                 closest_);
    cache.select({shaders::trace_any_rq, "trace_any_rq", bytes, workgroupSize_, gpu::FEATURE_GEOMETRY}, features, any_);
}

void RayQueryTraversal::dispatch(VkCommandBuffer cmd, const Scene& scene, const RayQueryLaunch& launch) {
    if (scene.traversal() != Traversal::RayQuery)
        throw std::runtime_error("ray-query tracing of a Scene built without acceleration structures: build the Scene "
                                 "with Traversal::RayQuery (or Auto, resolved the same way as the trace kernels)");
    if (launch.rayCount == 0 && launch.rayCountAddress == 0) return;
    vk::ComputePipeline& pipeline = launch.anyHit ? any_ : closest_;
    if (pipeline.handle() == VK_NULL_HANDLE)
        throw std::logic_error("RayQueryTraversal::dispatch before useFeatures built its pipelines");
    pipeline.bind(cmd);
    gpu::TraceParams params{};
    params.scene = scene.descAddress();
    params.rays = launch.rays;
    params.hits = launch.results;
    if (launch.rayCountAddress != 0) {
        params.rayCountAddress = launch.rayCountAddress;
        pipeline.pushConstants(cmd, &params, sizeof(params));
        vkCmdDispatchIndirect(cmd, launch.indirectBuffer, launch.indirectOffset);
        return;
    }
    const VkDeviceSize resultStride = launch.anyHit ? sizeof(uint32_t) : sizeof(gpu::Hit);
    const uint64_t maxRaysPerDispatch = uint64_t(context_.properties().limits.maxComputeWorkGroupCount[0]) * workgroupSize_;
    for (uint64_t first = 0; first < launch.rayCount; first += maxRaysPerDispatch) {
        const auto count = static_cast<uint32_t>(std::min<uint64_t>(maxRaysPerDispatch, launch.rayCount - first));
        params.rays = launch.rays + first * sizeof(gpu::Ray);
        params.hits = launch.results + first * resultStride;
        params.rayCount = count;
        pipeline.pushConstants(cmd, &params, sizeof(params));
        pipeline.dispatch(cmd, (count + workgroupSize_ - 1) / workgroupSize_);
    }
}

}  // namespace ripple::core
