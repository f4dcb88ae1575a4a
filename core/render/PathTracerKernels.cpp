// The path tracer's kernels (fixed, or specialised per FeatureSet), its frame and queue buffers, and the
// helpers that submit and dispatch its stages and read their counters.
#include "core/render/PathTracerImpl.h"

#include "shaders/pt_accumulate.spv.h"
#include "shaders/pt_generate.spv.h"
#include "shaders/pt_queue_advance.spv.h"
#include "shaders/pt_resolve.spv.h"
#include "shaders/pt_shade.spv.h"
#include "shaders/pt_shadow_resolve.spv.h"
#include "shaders/pt_shadow_volume.spv.h"
#include "shaders/pt_volume.spv.h"
#include "shaders/pt_surface.spv.h"

#include <algorithm>
#include <cstddef>
#include <future>
#include <stdexcept>
#include <string>

namespace ripple::core {

namespace {

constexpr uint32_t kWorkgroupSizeConstant = 0;  // layout(local_size_x_id = 0) in pt_common.glsl

}  // namespace

PathTracer::Impl::Impl(const vk::Context& ctx, const TraceOptions& traceOptions, const PathTracerOptions& opts)
    : context(ctx), options(opts), trace(ctx, traceOptions), parking(ctx, opts.volumeParking), pipelines(ctx),
      shadePipelines(ctx), channels(ctx, opts.workgroupSize), visitors(ctx, trace, opts.workgroupSize), profile(ctx) {
    if (options.queueCapacity == 0 || options.workgroupSize == 0)
        throw std::invalid_argument("PathTracerOptions: queueCapacity and workgroupSize must be positive");
    fixedKernels = std::async(std::launch::async, [this] {
        generate = stageKernel(shaders::pt_generate, "pt_generate");
        shadowResolve = stageKernel(shaders::pt_shadow_resolve, "pt_shadow_resolve");
        accumulate = stageKernel(shaders::pt_accumulate, "pt_accumulate");
        resolve = stageKernel(shaders::pt_resolve, "pt_resolve");
        queueAdvance = vk::ComputePipeline(context, shaders::pt_queue_advance, "pt_queue_advance",
                                           static_cast<uint32_t>(sizeof(gpu::QueueAdvanceParams)));
    });
    frame = vk::Buffer(ctx, sizeof(gpu::FrameConstants), "path tracer frame constants");
    // Host-visible on every device: the host reads the queue counts (after each bounce with several
    // ranks, after a wave with one). Also the indirect dispatch sizes of the queue stages.
    counters = vk::Buffer(ctx, sizeof(gpu::PathCounters), "path tracer counters", VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                          vk::Buffer::Placement::HostStaging);
}

vk::ComputePipeline PathTracer::Impl::stageKernel(std::span<const uint32_t> spirv, const char* name) const {
    const vk::SpecializationConstant constants[] = {{kWorkgroupSizeConstant, options.workgroupSize}};
    return vk::ComputePipeline(context, spirv, name, static_cast<uint32_t>(sizeof(gpu::StageParams)), constants);
}

// Before any use of a fixed kernel; rethrows a failure to build one, at every call (the frame that
// reported it may be followed by others on the same tracer).
void PathTracer::Impl::kernelsBuilt() {
    if (fixedKernels.valid()) {
        try {
            fixedKernels.get();
        } catch (...) {
            kernelFailure = std::current_exception();
        }
    }
    if (kernelFailure) std::rethrow_exception(kernelFailure);
}

// The kernels the FeatureSet `bits` specialise, and the volume kernels when it has volumes, built where
// missing: the trace kernels and pt_shade on threads of their own while this one builds pt_surface.
void PathTracer::Impl::selectKernels(uint32_t bits) {
    if (kernelFeatures == bits) return;
    auto traced = std::async(std::launch::async, [&] { trace.useFeatures(bits); });
    // With several ranks, a path's home also shades what the other ranks' surfaces and volumes packed,
    // whose materials this rank's FeatureSet does not know: there pt_shade keeps every material model.
    // (Lights are gathered from every rank, so their kinds are known.)
    const uint32_t materialModels = gpu::FEATURE_VOLUMES | gpu::FEATURE_PHYSICALLY_BASED | gpu::FEATURE_CLEARCOAT |
                                    gpu::FEATURE_TRANSMISSION;
    const uint32_t shadeBits = bits & gpu::FEATURE_MULTI_RANK ? bits | materialModels : bits;
    auto shaded = std::async(std::launch::async, [&] {
        shadePipelines.select({shaders::pt_shade, "pt_shade", static_cast<uint32_t>(sizeof(gpu::StageParams)),
                               options.workgroupSize, gpu::FEATURE_LIGHTS | materialModels},
                              shadeBits, shade);
    });
    try {
        pipelines.select({shaders::pt_surface, "pt_surface", static_cast<uint32_t>(sizeof(gpu::StageParams)),
                          options.workgroupSize,
                          gpu::FEATURE_GEOMETRY | gpu::FEATURE_TEXTURES | gpu::FEATURE_SURFACE_CHANNELS},
                         bits, surface);
        if (bits & gpu::FEATURE_VOLUMES) {
            // Specialised on the kinds of volume the world has: meshes, NanoVDB grids and AMR hierarchies bring code
            // of their own.
            const uint32_t volumeKinds = gpu::FEATURE_UNSTRUCTURED_VOLUMES | gpu::FEATURE_NANOVDB_VOLUMES | gpu::FEATURE_AMR_VOLUMES;
            const uint32_t stageBytes = static_cast<uint32_t>(sizeof(gpu::StageParams));
            pipelines.select({shaders::pt_volume, "pt_volume", stageBytes, options.workgroupSize, volumeKinds}, bits, volume);
            pipelines.select({shaders::pt_shadow_volume, "pt_shadow_volume", stageBytes, options.workgroupSize, volumeKinds},
                             bits, shadowVolume);
        }
    } catch (...) {
        traced.wait();  // they refer to this frame's locals
        shaded.wait();
        throw;
    }
    traced.get();
    shaded.get();
    kernelsBuilt();
    kernelFeatures = bits;
}

// Room for at least `paths` in flight and `slots` sample slots of a pass; resize() sets it for one sample
// of each pixel per pass, render() enlarges it for several.
void PathTracer::Impl::reserve(uint64_t paths, uint64_t slots) {
    if (paths > capacity) allocatePaths(static_cast<uint32_t>(paths));
    if (slots > sampleSlots) {
        sampleSlots = slots;
        sampleRadiance = vk::Buffer(context, slots * sizeof(gpu::vec4), "frame sample radiance");
    }
}

void PathTracer::Impl::allocatePaths(uint32_t paths) {
    capacity = paths;
    for (int q = 0; q < 2; ++q) {
        queues[q].paths = vk::Buffer(context, uint64_t(paths) * sizeof(gpu::PathState), "path queue " + std::to_string(q) + " states");
        queues[q].rays = vk::Buffer(context, uint64_t(paths) * sizeof(gpu::Ray), "path queue " + std::to_string(q) + " rays");
    }
    hits = vk::Buffer(context, uint64_t(paths) * sizeof(gpu::Hit), "path hits");
    surfaces = vk::Buffer(context, uint64_t(paths) * sizeof(gpu::SurfaceRecord), "path surface records");
    shadowRays = vk::Buffer(context, uint64_t(paths) * sizeof(gpu::Ray), "shadow rays");
    shadowRequests = vk::Buffer(context, uint64_t(paths) * sizeof(gpu::ShadowRequest), "shadow requests");
    occlusion = vk::Buffer(context, uint64_t(paths) * sizeof(uint32_t), "shadow occlusion");
}

// Camera and settings plus the frame's buffer addresses. resize() uploads it too (with no camera), so
// readColor before the first render reads valid addresses.
void PathTracer::Impl::uploadFrame(gpu::FrameConstants f, glm::uvec2 size) {
    f.width = size.x;
    f.height = size.y;
    f.sampleRadiance = sampleRadiance.address();
    f.accumulation = accumulation.address();
    f.sampleCount = sampleCount.address();
    f.depth = vk::addressOf(depth);
    f.counters = counters.address();
    frame.upload(&f, sizeof(f));
}

// Makes the kernels' counter updates visible to the host once the submission has finished.
void PathTracer::Impl::hostReadBarrier(VkCommandBuffer cmd) {
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
}

gpu::PathCounters PathTracer::Impl::readCounters() const {
    gpu::PathCounters c{};
    counters.download(&c, sizeof(c));
    return c;
}

// What the frame's kernels counted over all its passes, read after the last one.
void PathTracer::Impl::readFrameCounters(FrameStats& stats) const {
    const gpu::PathCounters c = readCounters();
    stats.nonFiniteSamples = c.nonFinite;
    stats.flaggedRays = c.flagged;
    auto sum64 = [](const uint32_t (&words)[2]) { return uint64_t(words[0]) | (uint64_t(words[1]) << 32); };
    stats.realCollisions = sum64(c.realCollisions);
    stats.nullCollisions = sum64(c.nullCollisions);
    stats.ratioCollisions = sum64(c.ratioCollisions);
    stats.parkedMarches = sum64(c.parkedMarches);
}

gpu::StageParams PathTracer::Impl::params(const Scene* scene) const {
    gpu::StageParams p{};
    p.frame = frame.address();
    p.scene = scene ? scene->descAddress() : 0;
    return p;
}

// The most items one dispatch covers: the device's workgroup-count limit times the workgroup size.
uint64_t PathTracer::Impl::itemsPerDispatch() const {
    return uint64_t(context.properties().limits.maxComputeWorkGroupCount[0]) * options.workgroupSize;
}

uint64_t PathTracer::Impl::pathLimit() const {
    const uint32_t workgroup = std::min(options.workgroupSize, trace.options().workgroupSize);
    return std::min<uint64_t>(options.queueCapacity,
                              uint64_t(context.properties().limits.maxComputeWorkGroupCount[0]) * workgroup);
}

// One stage over `count` items, in as many dispatches as the device's workgroup-count limit needs;
// firstPixel advances with each one (only the per-pixel stages get more than one: queues are capped
// to one dispatch in resize).
void PathTracer::Impl::dispatch(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline, gpu::StageParams p,
                                uint64_t count) {
    vk::computeBarrier(cmd);
    pipeline.bind(cmd);
    const uint64_t perDispatch = itemsPerDispatch();
    for (uint64_t done = 0; done < count; done += perDispatch) {
        gpu::StageParams chunk = p;
        chunk.count = static_cast<uint32_t>(std::min(perDispatch, count - done));
        chunk.firstPixel = p.firstPixel + static_cast<uint32_t>(done);
        pipeline.pushConstants(cmd, &chunk, sizeof(chunk));
        pipeline.dispatch(cmd, (chunk.count + options.workgroupSize - 1) / options.workgroupSize);
    }
}

// A queue stage over the path queue (COUNT_PATH_QUEUE) or the shadow queue (COUNT_SHADOW_QUEUE): launched
// indirectly with its length on the device, or with the host's count.
void PathTracer::Impl::dispatchQueue(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline, gpu::StageParams p,
                                     uint32_t queue, uint32_t hostCount) {
    if (!lengthsOnDevice) {
        dispatch(cmd, pipeline, p, hostCount);
        return;
    }
    vk::computeBarrier(cmd);
    pipeline.bind(cmd);
    p.countSource = queue;
    pipeline.pushConstants(cmd, &p, sizeof(p));
    vkCmdDispatchIndirect(cmd, counters.handle(), queue == gpu::COUNT_PATH_QUEUE
                                                      ? offsetof(gpu::PathCounters, pathGroups)
                                                      : offsetof(gpu::PathCounters, shadowGroups));
}

// A volume stage over a queue, as dispatchQueue, then the resume rounds of marches it parks.
void PathTracer::Impl::dispatchVolumeStage(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline,
                                           gpu::StageParams p, uint32_t queue, uint32_t hostCount) {
    VolumeParking::Launch launch{hostCount, nullptr, 0, options.workgroupSize};
    if (lengthsOnDevice) {
        p.countSource = queue;
        launch.indirect = &counters;
        launch.indirectOffset = queue == gpu::COUNT_PATH_QUEUE ? offsetof(gpu::PathCounters, pathGroups)
                                                              : offsetof(gpu::PathCounters, shadowGroups);
    } else {
        p.count = hostCount;
    }
    parking.run(cmd, pipeline, p, capacity, launch);
}

DeviceRayCount PathTracer::Impl::deviceRayCount(uint32_t queue) const {
    const bool paths = queue == gpu::COUNT_PATH_QUEUE;
    return {&counters, paths ? offsetof(gpu::PathCounters, pathCount) : offsetof(gpu::PathCounters, shadowCount),
            paths ? offsetof(gpu::PathCounters, pathTraceGroups) : offsetof(gpu::PathCounters, shadowTraceGroups)};
}

}  // namespace ripple::core
