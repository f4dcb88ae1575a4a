// Host side of the trace kernels: launches closest-hit or any-hit traversal over a batch of rays, then
// up to `resumeRounds` indirect dispatches that continue traversals which spent their step budget.
#include "core/render/TraceKernels.h"

#include "shaders/trace_any.spv.h"
#include "shaders/trace_closest.spv.h"

#include <algorithm>

namespace ripple::core {

namespace {

void resetResumePool(VkCommandBuffer cmd, const vk::Buffer& pool) {
    const gpu::ResumeHeader emptyHeader{0, 0, 1, 1};
    vkCmdUpdateBuffer(cmd, pool.handle(), 0, sizeof(emptyHeader), &emptyHeader);
    vk::computeBarrier(cmd);
}

}  // namespace

TraceKernels::TraceKernels(const vk::Context& context, const TraceOptions& options)
    : context_(context), options_(options), pipelines_(context) {
    if (options_.stepBudget < kMinStepBudget || options_.stepBudget > kMaxStepBudget)
        throw std::invalid_argument("TraceOptions::stepBudget must be in [" + std::to_string(kMinStepBudget) + ", " +
                                    std::to_string(kMaxStepBudget) + "], not " + std::to_string(options_.stepBudget));
    // A resume round's workgroups are counted by the kernel from the rays parked in its pool
    // (traverse.glsl), so a pool of at most one dispatch's worth keeps those indirect dispatches within the
    // device's maxComputeWorkGroupCount (the default 2^14 is far below it but for lowered limits).
    const uint64_t perDispatch = uint64_t(context.properties().limits.maxComputeWorkGroupCount[0]) * options_.workgroupSize;
    options_.resumeCapacity = static_cast<uint32_t>(std::min<uint64_t>(options_.resumeCapacity, perDispatch));
    traversal_ = resolveTraversal(context, options_.traversal);
    if (traversal_ == Traversal::RayQuery) rayQuery_ = std::make_unique<RayQueryTraversal>(context, options_.workgroupSize);
    // The pipelines are built when the first trace needs them, for the features chosen by then: building
    // a variant that is replaced before it runs cost about 80 ms of a start-up on lavapipe
    // (and the surface stage's 300 ms, PathTracerKernels.cpp).
}

void TraceKernels::useFeatures(uint32_t features) {
    featuresChosen_ = true;
    if (rayQuery_) return rayQuery_->useFeatures(features, pipelines_);
    const auto bytes = static_cast<uint32_t>(sizeof(gpu::TraceParams));
    pipelines_.select({shaders::trace_closest, "trace_closest", bytes, options_.workgroupSize, gpu::FEATURE_GEOMETRY},
                      features, closest_);
    pipelines_.select({shaders::trace_any, "trace_any", bytes, options_.workgroupSize, gpu::FEATURE_GEOMETRY},
                      features, any_);
}

void TraceKernels::ensureResumePools() {
    if (options_.resumeRounds == 0 || resumePools_[0]) return;
    const VkDeviceSize bytes = sizeof(gpu::ResumeHeader) + VkDeviceSize(options_.resumeCapacity) * sizeof(gpu::TraversalState);
    for (int i = 0; i < 2; ++i)
        resumePools_[i] = vk::Buffer(context_, bytes, "trace resume pool " + std::to_string(i),
                                     VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
}

void TraceKernels::dispatch(VkCommandBuffer cmd, vk::ComputePipeline& pipeline, const Scene& scene,
                            const vk::Buffer& rays, const vk::Buffer& results, uint32_t rayCount,
                            const DeviceRayCount* deviceCount) {
    if (rayCount == 0 && !deviceCount) return;
    if (!featuresChosen_) useFeatures(gpu::FEATURE_ALL);
    if (rayQuery_) {  // no step budget and no resume rounds with ray queries
        rayQuery_->dispatch(cmd, scene, {&pipeline == &any_, rays.address(), results.address(), rayCount,
                                         deviceCount ? deviceCount->buffer->address() + deviceCount->countOffset : 0,
                                         deviceCount ? deviceCount->buffer->handle() : VK_NULL_HANDLE,
                                         deviceCount ? deviceCount->groupsOffset : 0});
        return;
    }
    ensureResumePools();
    const bool resumable = options_.resumeRounds > 0;
    const VkDeviceSize resultStride = &pipeline == &any_ ? sizeof(uint32_t) : sizeof(gpu::Hit);

    pipeline.bind(cmd);
    if (resumable) resetResumePool(cmd, resumePools_[0]);

    gpu::TraceParams params{};
    params.scene = scene.descAddress();
    params.rays = rays.address();
    params.hits = results.address();
    params.resumeOut = resumable ? resumePools_[0].address() : 0;
    params.resumeCapacity = options_.resumeCapacity;
    params.stepBudget = options_.stepBudget;
    if (deviceCount) {
        params.rayCountAddress = deviceCount->buffer->address() + deviceCount->countOffset;
        pipeline.pushConstants(cmd, &params, sizeof(params));
        vkCmdDispatchIndirect(cmd, deviceCount->buffer->handle(), deviceCount->groupsOffset);
        resumeRounds(cmd, pipeline, params);
        return;
    }

    // Fresh rays, in chunks that respect the device's limit on workgroups per dispatch.
    const uint64_t maxRaysPerDispatch = uint64_t(context_.properties().limits.maxComputeWorkGroupCount[0]) * options_.workgroupSize;
    for (uint64_t first = 0; first < rayCount; first += maxRaysPerDispatch) {
        const uint32_t count = static_cast<uint32_t>(std::min<uint64_t>(maxRaysPerDispatch, rayCount - first));
        gpu::TraceParams chunk = params;
        chunk.rays = rays.address() + first * sizeof(gpu::Ray);
        chunk.hits = results.address() + first * resultStride;
        chunk.rayCount = count;
        pipeline.pushConstants(cmd, &chunk, sizeof(chunk));
        pipeline.dispatch(cmd, (count + options_.workgroupSize - 1) / options_.workgroupSize);
        // Parked states hold ray indices relative to this chunk's base addresses, so each chunk finishes
        // its rounds before the next chunk starts.
        resumeRounds(cmd, pipeline, chunk);
        if (resumable && first + count < rayCount) {
            vk::computeBarrier(cmd);
            resetResumePool(cmd, resumePools_[0]);
        }
    }
}

// Resume rounds: indirect dispatches sized by the kernel itself, so the host never reads a count.
void TraceKernels::resumeRounds(VkCommandBuffer cmd, vk::ComputePipeline& pipeline, gpu::TraceParams params) {
    for (uint32_t round = 1; round <= options_.resumeRounds; ++round) {
        const int in = (round - 1) % 2, out = round % 2;
        const bool last = round == options_.resumeRounds;
        vk::computeBarrier(cmd);
        if (!last) resetResumePool(cmd, resumePools_[out]);
        params.resumeIn = resumePools_[in].address();
        params.resumeOut = last ? 0 : resumePools_[out].address();
        pipeline.pushConstants(cmd, &params, sizeof(params));
        vkCmdDispatchIndirect(cmd, resumePools_[in].handle(), offsetof(gpu::ResumeHeader, groupsX));
    }
}

void TraceKernels::traceClosest(VkCommandBuffer cmd, const Scene& scene, const vk::Buffer& rays, const vk::Buffer& hits,
                                const DeviceRayCount& count) {
    dispatch(cmd, closest_, scene, rays, hits, 0, &count);
}

void TraceKernels::traceAny(VkCommandBuffer cmd, const Scene& scene, const vk::Buffer& rays, const vk::Buffer& occluded,
                            const DeviceRayCount& count) {
    dispatch(cmd, any_, scene, rays, occluded, 0, &count);
}

void TraceKernels::traceClosest(VkCommandBuffer cmd, const Scene& scene, const vk::Buffer& rays, const vk::Buffer& hits,
                                uint32_t rayCount) {
    dispatch(cmd, closest_, scene, rays, hits, rayCount);
}

void TraceKernels::traceAny(VkCommandBuffer cmd, const Scene& scene, const vk::Buffer& rays, const vk::Buffer& occluded,
                            uint32_t rayCount) {
    dispatch(cmd, any_, scene, rays, occluded, rayCount);
}

template <class Result>
std::vector<Result> TraceKernels::traceOnHost(vk::ComputePipeline& pipeline, const Scene& scene,
                                              std::span<const gpu::Ray> rays) {
    std::vector<Result> results(rays.size());
    if (rays.empty()) return results;
    vk::Buffer rayBuffer(context_, rays.size_bytes(), "trace rays");
    vk::Buffer resultBuffer(context_, results.size() * sizeof(Result), "trace results");
    rayBuffer.upload(rays);
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        dispatch(cmd, pipeline, scene, rayBuffer, resultBuffer, static_cast<uint32_t>(rays.size()));
    });
    resultBuffer.download(std::span(results));
    return results;
}

std::vector<gpu::Hit> TraceKernels::traceClosest(const Scene& scene, std::span<const gpu::Ray> rays) {
    return traceOnHost<gpu::Hit>(closest_, scene, rays);
}

std::vector<uint32_t> TraceKernels::traceAny(const Scene& scene, std::span<const gpu::Ray> rays) {
    return traceOnHost<uint32_t>(any_, scene, rays);
}

}  // namespace ripple::core
