// The path tracer's state and the methods that record its stages, private to core/render: PathTracer.cpp
// (the public API), PathTracerKernels.cpp and PathTracerWaves.cpp share it.
#pragma once

#include "core/render/PathTracer.h"

#include "core/render/PixelTiles.h"
#include "core/render/VisitorTracer.h"
#include "core/render/VolumeParking.h"
#include "core/vk/ComputePipeline.h"
#include "shaders/shared/path.h"

#include <algorithm>
#include <cstdint>
#include <exception>
#include <future>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace ripple::core {

struct PathTracer::Impl {
    struct Queue {
        vk::Buffer paths;  // gpu::PathState
        vk::Buffer rays;   // gpu::Ray
    };

    const vk::Context& context;
    PathTracerOptions options;
    TraceKernels trace;
    vk::ComputePipeline generate, surface, shade, shadowResolve, accumulate, resolve, queueAdvance;
    vk::ComputePipeline volume, shadowVolume;                       // built for the first world with volumes
    VolumeParking parking;                                          // their marches' resume rounds
    vk::Buffer frame, counters;                                     // FrameConstants, PathCounters
    vk::Buffer accumulation, sampleCount, depth, color;             // per pixel
    vk::Buffer sampleRadiance;                                      // per sample slot of a pass (pixels or more)
    Queue queues[2];
    int current = 0;                                                // the queue the next bounce consumes
    vk::Buffer hits, surfaces, shadowRays, shadowRequests, occlusion; // per path in flight
    uint32_t capacity = 0;                                          // paths in flight
    uint64_t sampleSlots = 0;                                       // sample radiance entries
    bool lengthsOnDevice = false;                                   // one rank: see PathTracerWaves.cpp
    uint32_t stratifiedSample = 0;                                  // the sample's StageParams::stratifiedSample
    LocalRayExchange localExchange;
    PipelineCache pipelines;                                        // variants of `surface` per FeatureSet
    PipelineCache shadePipelines;                                   // and of `shade` (built beside it)
    SurfaceChannels channels;                                       // albedo, normal and id channels
    uint32_t channelBits = 0;                                       // FEATURE_CHANNEL_* asked for in resize
    FeatureSet features = FeatureSet::all();                        // of the latest render
    VisitorTracer visitors;                                         // traces rays from other ranks
    StageProfile profile;                                           // GPU time per stage
    StageSeconds stageSeconds{};                                    // of the frame being rendered
    std::optional<uint32_t> kernelFeatures;  // what selectKernels last selected for
    std::exception_ptr kernelFailure;        // a fixed kernel's build failed
    // The kernels every frame runs compile on a thread of their own while the caller builds its scene
    // (lavapipe compiles each with LLVM: 0.1 s together on the main job); kernelsBuilt() waits for them.
    // Last member, so that it is joined before the pipelines it writes are destroyed.
    std::future<void> fixedKernels;

    Impl(const vk::Context& ctx, const TraceOptions& traceOptions, const PathTracerOptions& opts);

    // Kernels and buffers (PathTracerKernels.cpp).
    vk::ComputePipeline stageKernel(std::span<const uint32_t> spirv, const char* name) const;
    void kernelsBuilt();
    void selectKernels(uint32_t bits);
    void reserve(uint64_t paths, uint64_t slots);
    void allocatePaths(uint32_t paths);
    void uploadFrame(gpu::FrameConstants f, glm::uvec2 size);

    // Submissions, dispatches and counters (PathTracerKernels.cpp).
    static void hostReadBarrier(VkCommandBuffer cmd);
    // A submission whose stages (mark) are timed into stageSeconds.
    template <class Record>
    void submitTimed(Record&& record) {
        context.submitAndWait([&](VkCommandBuffer cmd) {
            profile.begin(cmd);
            record(cmd);
        });
        profile.collect(stageSeconds);
    }
    void mark(VkCommandBuffer cmd, Stage stage) { profile.mark(cmd, stage); }
    gpu::PathCounters readCounters() const;
    void writeCounters(const gpu::PathCounters& c) { counters.upload(&c, sizeof(c)); }
    void readFrameCounters(FrameStats& stats) const;
    gpu::StageParams params(const Scene* scene) const;
    uint64_t itemsPerDispatch() const;
    // The most paths in flight: the queue capacity, within one dispatch (queue stages index their queue by
    // invocation, so one dispatch must cover a whole queue), also of the trace kernels, whose indirect
    // dispatches over a queue count in their own workgroup size.
    uint64_t pathLimit() const;
    void dispatch(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline, gpu::StageParams p, uint64_t count);
    void dispatchQueue(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline, gpu::StageParams p, uint32_t queue,
                       uint32_t hostCount);
    void dispatchVolumeStage(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline, gpu::StageParams p,
                             uint32_t queue, uint32_t hostCount);
    DeviceRayCount deviceRayCount(uint32_t queue) const;

    // Passes and waves, the stages of a wave and the bounce loops (PathTracerWaves.cpp).
    uint32_t samplesPerPass(uint64_t pixels, uint64_t busiest, uint32_t pixelSamples) const;
    std::vector<Wave> passWaves(const std::vector<PixelRange>& owned, uint32_t pixels, uint32_t samples) const;
    RayExchange& exchange() { return options.exchange ? *options.exchange : localExchange; }
    void advanceQueueLengths(VkCommandBuffer cmd);
    void generateRays(VkCommandBuffer cmd, const Wave& wave, uint32_t sampleIndex);
    void occlude(VkCommandBuffer cmd, const Scene& scene, uint32_t count);
    void resolveShadows(VkCommandBuffer cmd, const Scene& scene, uint32_t count, uint32_t bounce, uint32_t sampleIndex);
    void traceAndShade(VkCommandBuffer cmd, const Scene& scene, uint32_t count, uint32_t bounce, uint32_t sampleIndex);
    void shadePaths(VkCommandBuffer cmd, const Scene& scene, uint32_t count, uint32_t bounce, uint32_t sampleIndex);
    void exchangeRays(const Scene& scene, uint32_t paths, uint32_t shadows, uint32_t bounce, uint32_t sampleIndex);
    void traceWave(const Scene& scene, const Wave& wave, uint32_t sampleIndex, uint32_t firstBatch, uint32_t maxBounces,
                   FrameStats& stats);
    void traceWaveAcrossRanks(const Scene& scene, const Wave* wave, uint32_t sampleIndex, uint32_t maxBounces,
                              FrameStats& stats);
    std::pair<uint32_t, uint32_t> takeQueueCounts();
    void accumulatePass(const std::vector<PixelRange>& owned, uint32_t sampleIndex);
};

}  // namespace ripple::core
