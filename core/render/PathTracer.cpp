// Host side of the wavefront path tracer: frame and queue buffers, and the loop that dispatches the
// pt_*.comp stages. With one rank the queue lengths stay on the device (pt_queue_advance sizes the next
// bounce's indirect dispatches), so a wave's bounces are one submission and the host only checks once,
// after the bounces a path without pass-throughs can take, whether any path remains. With several ranks
// the host reads the lengths after every bounce: the exchange and its allreduce need them.
#include "core/render/PathTracer.h"

#include "core/render/CameraRays.h"
#include "core/render/PixelTiles.h"
#include "core/render/VisitorTracer.h"
#include "core/render/VolumeParking.h"
#include "core/vk/ComputePipeline.h"
#include "shaders/pt_accumulate.spv.h"
#include "shaders/pt_generate.spv.h"
#include "shaders/pt_queue_advance.spv.h"
#include "shaders/pt_resolve.spv.h"
#include "shaders/pt_shade.spv.h"
#include "shaders/pt_shadow_resolve.spv.h"
#include "shaders/pt_shadow_volume.spv.h"
#include "shaders/pt_volume.spv.h"
#include "shaders/pt_surface.spv.h"
#include "shaders/shared/path.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <exception>
#include <future>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>

namespace ripple::core {

namespace {

constexpr uint32_t kWorkgroupSizeConstant = 0;  // layout(local_size_x_id = 0) in pt_common.glsl

// Camera and settings as the kernels read them; throws std::invalid_argument for a camera that cannot
// produce rays.
gpu::FrameConstants frameConstants(const Camera& camera, const RenderSettings& settings) {
    gpu::FrameConstants f{};
    writeCamera(camera, f);
    f.background = settings.background;
    f.ambient = gpu::vec4(settings.ambientColor * settings.ambientRadiance, 0.0f);
    f.maxPathLength = std::max(1u, settings.maxPathLength);
    f.seed = settings.seed;
    f.maxRadiance = settings.maxRadiance > 0.0f && std::isfinite(settings.maxRadiance) ? settings.maxRadiance : 0.0f;
    // |g| below 1e-3 is sampled as isotropic (pt_shade.comp), so it is evaluated as isotropic too.
    f.phaseAnisotropy = std::isfinite(settings.phaseAnisotropy) && std::abs(settings.phaseAnisotropy) >= 1e-3f
                            ? std::clamp(settings.phaseAnisotropy, -0.99f, 0.99f) : 0.0f;
    f.shading = settings.shading == RenderSettings::Shading::EyeLight ? gpu::SHADING_EYE_LIGHT : gpu::SHADING_PATH_TRACED;
    f.eyeLightBlendRatio = std::isfinite(settings.eyeLightBlendRatio) ? std::clamp(settings.eyeLightBlendRatio, 0.0f, 1.0f) : 0.5f;
    f.lightSampling = static_cast<uint32_t>(settings.lightSampling) <= gpu::LIGHT_SAMPLING_BSDF_ONLY
                          ? static_cast<uint32_t>(settings.lightSampling) : gpu::LIGHT_SAMPLING_MIS;
    return f;
}

}  // namespace

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
    bool lengthsOnDevice = false;                                   // one rank: see the header comment
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

    Impl(const vk::Context& ctx, const TraceOptions& traceOptions, const PathTracerOptions& opts)
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

    vk::ComputePipeline stageKernel(std::span<const uint32_t> spirv, const char* name) const {
        const vk::SpecializationConstant constants[] = {{kWorkgroupSizeConstant, options.workgroupSize}};
        return vk::ComputePipeline(context, spirv, name, static_cast<uint32_t>(sizeof(gpu::StageParams)), constants);
    }

    // Before any use of a fixed kernel; rethrows a failure to build one, at every call (the frame that
    // reported it may be followed by others on the same tracer).
    void kernelsBuilt() {
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
    void selectKernels(uint32_t bits) {
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
            if ((bits & gpu::FEATURE_VOLUMES) && volume.handle() == VK_NULL_HANDLE) {
                volume = stageKernel(shaders::pt_volume, "pt_volume");
                shadowVolume = stageKernel(shaders::pt_shadow_volume, "pt_shadow_volume");
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
    void reserve(uint64_t paths, uint64_t slots) {
        if (paths > capacity) allocatePaths(static_cast<uint32_t>(paths));
        if (slots > sampleSlots) {
            sampleSlots = slots;
            sampleRadiance = vk::Buffer(context, slots * sizeof(gpu::vec4), "frame sample radiance");
        }
    }

    void allocatePaths(uint32_t paths) {
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

    // How many of each pixel's samples a pass of this frame traces together, the same on every rank: as many
    // as keep the busiest rank's pass (`busiest` pixels a sample) within options.packedWavePaths and one
    // dispatch, and the pass's sample slots (all pixels times the samples) within the queue capacity.
    uint32_t samplesPerPass(uint64_t pixels, uint64_t busiest, uint32_t pixelSamples) const {
        const uint64_t paths = std::min<uint64_t>(options.packedWavePaths, pathLimit());
        if (busiest == 0 || busiest * 2 > paths) return 1;
        const uint64_t samples = std::min<uint64_t>({pixelSamples, paths / busiest, options.queueCapacity / pixels});
        return static_cast<uint32_t>(std::max<uint64_t>(samples, 1));
    }

    // Camera and settings plus the frame's buffer addresses. resize() uploads it too (with no camera), so
    // readColor before the first render reads valid addresses.
    void uploadFrame(gpu::FrameConstants f, glm::uvec2 size) {
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
    static void hostReadBarrier(VkCommandBuffer cmd) {
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                             nullptr, 0, nullptr);
    }

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

    gpu::PathCounters readCounters() const {
        gpu::PathCounters c{};
        counters.download(&c, sizeof(c));
        return c;
    }
    void writeCounters(const gpu::PathCounters& c) { counters.upload(&c, sizeof(c)); }

    gpu::StageParams params(const Scene* scene) const {
        gpu::StageParams p{};
        p.frame = frame.address();
        p.scene = scene ? scene->descAddress() : 0;
        return p;
    }

    // The most items one dispatch covers: the device's workgroup-count limit times the workgroup size.
    uint64_t itemsPerDispatch() const {
        return uint64_t(context.properties().limits.maxComputeWorkGroupCount[0]) * options.workgroupSize;
    }

    // The most paths in flight: the queue capacity, within one dispatch (queue stages index their queue by
    // invocation, so one dispatch must cover a whole queue).
    uint64_t pathLimit() const { return std::min<uint64_t>(options.queueCapacity, itemsPerDispatch()); }

    // One stage over `count` items, in as many dispatches as the device's workgroup-count limit needs;
    // firstPixel advances with each one (only the per-pixel stages get more than one: queues are capped
    // to one dispatch in resize).
    void dispatch(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline, gpu::StageParams p, uint64_t count) {
        vk::computeBarrier(cmd);
        pipeline.bind(cmd);
        const uint64_t perDispatch = itemsPerDispatch();
        for (uint64_t done = 0; done < count; done += perDispatch) {
            gpu::StageParams chunk = p;
            chunk.count = static_cast<uint32_t>(std::min(perDispatch, count - done));
            chunk.firstPixel = p.firstPixel + static_cast<uint32_t>(done);
            pipeline.pushConstants(cmd, &chunk, sizeof(chunk));
            vkCmdDispatch(cmd, (chunk.count + options.workgroupSize - 1) / options.workgroupSize, 1, 1);
        }
    }

    // A queue stage over the path queue (COUNT_PATH_QUEUE) or the shadow queue (COUNT_SHADOW_QUEUE): launched
    // indirectly with its length on the device, or with the host's count.
    void dispatchQueue(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline, gpu::StageParams p, uint32_t queue,
                       uint32_t hostCount) {
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
    void dispatchVolumeStage(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline, gpu::StageParams p,
                             uint32_t queue, uint32_t hostCount) {
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

    DeviceRayCount deviceRayCount(uint32_t queue) const {
        const bool paths = queue == gpu::COUNT_PATH_QUEUE;
        return {&counters, paths ? offsetof(gpu::PathCounters, pathCount) : offsetof(gpu::PathCounters, shadowCount),
                paths ? offsetof(gpu::PathCounters, pathTraceGroups) : offsetof(gpu::PathCounters, shadowTraceGroups)};
    }

    // One rank, between bounces: what the bounce appended becomes the lengths the next one consumes (the
    // caller swaps `current`).
    void advanceQueueLengths(VkCommandBuffer cmd) {
        vk::computeBarrier(cmd);
        queueAdvance.bind(cmd);
        const gpu::QueueAdvanceParams p{counters.address(), capacity, options.workgroupSize, trace.options().workgroupSize, 0};
        queueAdvance.pushConstants(cmd, &p, sizeof(p));
        vkCmdDispatch(cmd, 1, 1, 1);
        mark(cmd, Stage::QueueAdvance);
    }

    void generateRays(VkCommandBuffer cmd, const Wave& wave, uint32_t sampleIndex) {
        for (const WavePart& part : wave.parts) {
            gpu::StageParams p = params(nullptr);
            p.paths = queues[current].paths.address() + uint64_t(part.queueOffset) * sizeof(gpu::PathState);
            p.rays = queues[current].rays.address() + uint64_t(part.queueOffset) * sizeof(gpu::Ray);
            p.firstPixel = part.pixels.first;
            p.sampleIndex = sampleIndex;
            p.stratifiedSample = stratifiedSample;
            p.results = channels.tableAddress();
            dispatch(cmd, generate, p, part.pixels.count);
        }
        mark(cmd, Stage::Generate);
    }

    RayExchange& exchange() { return options.exchange ? *options.exchange : localExchange; }

    // Any-hit for the shadow rays of the previous bounce; their contributions follow the exchange.
    // (With lengths on the device the host's counts below are not used.)
    void occlude(VkCommandBuffer cmd, const Scene& scene, uint32_t count) {
        if (count == 0 && !lengthsOnDevice) return;
        vk::computeBarrier(cmd);
        if (lengthsOnDevice) trace.traceAny(cmd, scene, shadowRays, occlusion, deviceRayCount(gpu::COUNT_SHADOW_QUEUE));
        else trace.traceAny(cmd, scene, shadowRays, occlusion, count);
        mark(cmd, Stage::TraceAny);
    }

    void resolveShadows(VkCommandBuffer cmd, const Scene& scene, uint32_t count, uint32_t bounce, uint32_t sampleIndex) {
        if (count == 0 && !lengthsOnDevice) return;
        gpu::StageParams p = params(&scene);
        if (features.has(gpu::FEATURE_VOLUMES)) {  // transmittance of the volumes along each shadow ray
            gpu::StageParams v = p;
            v.shadowRays = shadowRays.address();
            v.shadowRequests = shadowRequests.address();
            v.bounce = bounce;
            v.sampleIndex = sampleIndex;
            dispatchVolumeStage(cmd, shadowVolume, v, gpu::COUNT_SHADOW_QUEUE, count);
            mark(cmd, Stage::ShadowVolume);
        }
        p.shadowRequests = shadowRequests.address();
        p.results = occlusion.address();
        dispatchQueue(cmd, shadowResolve, p, gpu::COUNT_SHADOW_QUEUE, count);
        mark(cmd, Stage::ShadowResolve);
    }

    // Closest hit for the current queue and the surface at each hit; shading follows the exchange.
    void traceAndShade(VkCommandBuffer cmd, const Scene& scene, uint32_t count, uint32_t bounce, uint32_t sampleIndex) {
        if (count == 0 && !lengthsOnDevice) return;
        const Queue& in = queues[current];
        vk::computeBarrier(cmd);
        if (lengthsOnDevice) trace.traceClosest(cmd, scene, in.rays, hits, deviceRayCount(gpu::COUNT_PATH_QUEUE));
        else trace.traceClosest(cmd, scene, in.rays, hits, count);
        mark(cmd, Stage::TraceClosest);
        gpu::StageParams p = params(&scene);
        p.paths = in.paths.address();
        p.rays = in.rays.address();
        p.hits = hits.address();
        p.surfaces = surfaces.address();
        dispatchQueue(cmd, surface, p, gpu::COUNT_PATH_QUEUE, count);
        mark(cmd, Stage::Surface);
        if (features.has(gpu::FEATURE_VOLUMES)) {  // free flight: a collision before the surface replaces it
            p.bounce = bounce;
            p.sampleIndex = sampleIndex;
            dispatchVolumeStage(cmd, volume, p, gpu::COUNT_PATH_QUEUE, count);
            mark(cmd, Stage::Volume);
        }
    }

    // Shading into the other queue and the shadow queue.
    void shadePaths(VkCommandBuffer cmd, const Scene& scene, uint32_t count, uint32_t bounce, uint32_t sampleIndex) {
        if (count == 0 && !lengthsOnDevice) return;
        const Queue& in = queues[current];
        const Queue& out = queues[1 - current];
        gpu::StageParams p = params(&scene);
        p.paths = in.paths.address();
        p.rays = in.rays.address();
        p.hits = hits.address();
        p.surfaces = surfaces.address();
        p.bounce = bounce;
        p.sampleIndex = sampleIndex;
        p.stratifiedSample = stratifiedSample;
        if (bounce == 0 && channels.any()) {  // the camera rays' first hits fill the surface channels
            gpu::StageParams c = p;
            c.results = channels.tableAddress();
            dispatchQueue(cmd, channels.pipeline(), c, gpu::COUNT_PATH_QUEUE, count);
            mark(cmd, Stage::Channels);
        }
        p.nextPaths = out.paths.address();
        p.nextRays = out.rays.address();
        p.shadowRays = shadowRays.address();
        p.shadowRequests = shadowRequests.address();
        dispatchQueue(cmd, shade, p, gpu::COUNT_PATH_QUEUE, count);
        mark(cmd, Stage::Shade);
    }

    // With more than one rank: the queues as traced here go round the other ranks and come back with
    // the globally closest hits (their records) and occlusion, ready to shade.
    void exchangeRays(const Scene& scene, uint32_t paths, uint32_t shadows, uint32_t bounce, uint32_t sampleIndex) {
        RayExchange& ranks = exchange();
        VisitorTracer::Volumes here;
        if (features.has(gpu::FEATURE_VOLUMES))
            here = {&volume, &shadowVolume, &parking, bounce, sampleIndex, ranks.rank()};
        visitors.use(scene, frame.address(), surface, here);
        std::vector<gpu::Ray> rays(std::max(paths, shadows));
        std::vector<gpu::SurfaceRecord> records(paths);
        if (paths > 0) {
            queues[current].rays.download(rays.data(), paths * sizeof(gpu::Ray));
            surfaces.download(records.data(), paths * sizeof(gpu::SurfaceRecord));
        }
        std::vector<WireRay> wire(paths);
        for (uint32_t i = 0; i < paths; ++i) wire[i] = WireRay{rays[i], ranks.rank(), i, 0, 0, records[i]};
        ranks.exchangeClosest(wire, visitors);
        if (wire.size() != paths) throw std::runtime_error("RayExchange: path rays came back in a different number");
        for (uint32_t i = 0; i < paths; ++i) records[i] = wire[i].record;
        if (paths > 0) surfaces.upload(records.data(), paths * sizeof(gpu::SurfaceRecord));

        std::vector<uint32_t> occluded(shadows);
        if (shadows > 0) {
            shadowRays.download(rays.data(), shadows * sizeof(gpu::Ray));
            occlusion.download(occluded.data(), shadows * sizeof(uint32_t));
        }
        std::vector<WireShadowRay> shadowWire(shadows);
        for (uint32_t i = 0; i < shadows; ++i) shadowWire[i] = WireShadowRay{rays[i], ranks.rank(), i, occluded[i], 1.0f};
        ranks.exchangeShadow(shadowWire, visitors);
        if (shadowWire.size() != shadows) throw std::runtime_error("RayExchange: shadow rays came back in a different number");
        for (uint32_t i = 0; i < shadows; ++i) occluded[i] = shadowWire[i].occlusion;
        if (shadows > 0) occlusion.upload(occluded.data(), shadows * sizeof(uint32_t));
        // The other ranks' volumes dim the shadow rays (this rank's own do in resolveShadows). Checked on
        // every rank: another rank may hold volumes where this one has none.
        const bool dimmed = std::any_of(shadowWire.begin(), shadowWire.end(),
                                        [](const WireShadowRay& s) { return s.transmittance != 1.0f; });
        if (dimmed) {
            std::vector<gpu::ShadowRequest> requests(shadows);
            shadowRequests.download(requests.data(), shadows * sizeof(gpu::ShadowRequest));
            for (uint32_t i = 0; i < shadows; ++i) requests[i].contribution *= shadowWire[i].transmittance;
            shadowRequests.upload(requests.data(), shadows * sizeof(gpu::ShadowRequest));
        }
    }

    // One rank: the bounces of a wave with the queue lengths on the device. The first submission holds the
    // bounces a path without pass-throughs can take; only where paths remain after it (pass-throughs of
    // alpha or invisible surfaces) do more follow, up to `maxBounces` in all.
    void traceWave(const Scene& scene, const Wave& wave, uint32_t sampleIndex, uint32_t firstBatch, uint32_t maxBounces,
                   FrameStats& stats) {
        gpu::PathCounters c = readCounters();  // keeps nonFinite and flagged, which count over the frame
        c.nextPaths = wave.paths;              // what generate appends: the first advance turns it into the queue
        c.shadowRays = c.pathCount = c.shadowCount = c.pathsTraced = c.shadowsTraced = 0;
        writeCounters(c);
        uint32_t bounce = 0;
        while (bounce <= maxBounces) {
            const uint32_t end = bounce == 0 ? std::min(firstBatch, maxBounces + 1) : maxBounces + 1;
            submitTimed([&](VkCommandBuffer cmd) {
                if (bounce == 0) {
                    generateRays(cmd, wave, sampleIndex);
                    advanceQueueLengths(cmd);
                }
                for (; bounce < end; ++bounce) {
                    occlude(cmd, scene, 0);
                    traceAndShade(cmd, scene, 0, bounce, sampleIndex);
                    resolveShadows(cmd, scene, 0, bounce, sampleIndex);
                    shadePaths(cmd, scene, 0, bounce, sampleIndex);
                    advanceQueueLengths(cmd);
                    current = 1 - current;
                }
                hostReadBarrier(cmd);
            });
            c = readCounters();
            if (c.pathCount + c.shadowCount == 0) break;
        }
        stats.raysTraced += c.pathsTraced;
        stats.shadowRays += c.shadowsTraced;
    }

    // Several ranks: a wave's bounces with the exchange between tracing and shading; every rank takes part
    // in each bounce until no rank has a path or shadow ray left (`wave` is null where this rank has none).
    void traceWaveAcrossRanks(const Scene& scene, const Wave* wave, uint32_t sampleIndex, uint32_t maxBounces,
                              FrameStats& stats) {
        RayExchange& ranks = exchange();
        uint32_t paths = wave ? wave->paths : 0, shadows = 0;
        for (uint32_t bounce = 0; bounce <= maxBounces && ranks.sum(paths + shadows) > 0; ++bounce) {
            submitTimed([&](VkCommandBuffer cmd) {
                if (bounce == 0 && paths > 0) generateRays(cmd, *wave, sampleIndex);
                occlude(cmd, scene, shadows);
                traceAndShade(cmd, scene, paths, bounce, sampleIndex);
                hostReadBarrier(cmd);
            });
            exchangeRays(scene, paths, shadows, bounce, sampleIndex);
            submitTimed([&](VkCommandBuffer cmd) {
                resolveShadows(cmd, scene, shadows, bounce, sampleIndex);
                shadePaths(cmd, scene, paths, bounce, sampleIndex);
                hostReadBarrier(cmd);
            });
            stats.raysTraced += paths;
            stats.shadowRays += shadows;
            std::tie(paths, shadows) = takeQueueCounts();
        }
    }

    // Several ranks, after a bounce: the lengths of the queues it filled, which become the ones to consume next.
    std::pair<uint32_t, uint32_t> takeQueueCounts() {
        gpu::PathCounters c = readCounters();
        const std::pair<uint32_t, uint32_t> counts{std::min(c.nextPaths, capacity), std::min(c.shadowRays, capacity)};
        c.nextPaths = c.shadowRays = 0;
        writeCounters(c);
        current = 1 - current;
        return counts;
    }
};

PathTracer::PathTracer(const vk::Context& context, const TraceOptions& traceOptions, const PathTracerOptions& options)
    : impl_(std::make_unique<Impl>(context, traceOptions, options)) {}

PathTracer::~PathTracer() = default;

void PathTracer::resize(glm::uvec2 size, bool wantDepth) { resize(size, FrameChannels{.depth = wantDepth}); }

void PathTracer::resize(glm::uvec2 size, const FrameChannels& channels) {
    const bool wantDepth = channels.depth;
    const uint64_t pixels = uint64_t(size.x) * size.y;
    if (pixels == 0 || pixels > UINT32_MAX)
        throw std::invalid_argument("PathTracer::resize: " + std::to_string(size.x) + "x" + std::to_string(size.y) +
                                    " pixels (need at least one, and fewer than 2^32)");
    Impl& m = *impl_;
    const vk::Context& ctx = m.context;
    m.accumulation = vk::Buffer(ctx, pixels * sizeof(gpu::vec4), "frame accumulation");
    m.sampleCount = vk::Buffer(ctx, pixels * sizeof(uint32_t), "frame sample count");
    m.depth = wantDepth ? vk::Buffer(ctx, pixels * sizeof(float), "frame depth") : vk::Buffer();
    m.color = vk::Buffer();  // allocated by the first readColor
    m.channels.resize(pixels, channels);
    m.channelBits = channelFeatures(channels);
    m.capacity = 0;
    m.sampleSlots = 0;
    m.reserve(std::min<uint64_t>(pixels, m.pathLimit()), pixels);
    size_ = size;
    m.uploadFrame(gpu::FrameConstants{}, size);
    resetAccumulation();
}

void PathTracer::resetAccumulation() {
    accumulatedSamples_ = 0;
    accumulatedFrames_ = 0;
    stratifiedSamples_[0] = stratifiedSamples_[1] = 0;
    if (size_.x == 0) return;
    const Impl& m = *impl_;
    m.context.submitAndWait([&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, m.accumulation.handle(), 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, m.sampleCount.handle(), 0, VK_WHOLE_SIZE, 0);
        if (m.depth) vkCmdFillBuffer(cmd, m.depth.handle(), 0, VK_WHOLE_SIZE, 0x7f800000u);  // +inf
    });
}

FrameStats PathTracer::render(const Scene& scene, const Camera& camera, const RenderSettings& settings) {
    if (size_.x == 0) throw std::invalid_argument("PathTracer::render: call resize() first");
    const auto start = std::chrono::steady_clock::now();
    Impl& m = *impl_;
    gpu::FrameConstants constants = frameConstants(camera, settings);
    constants.ambient.w = scene.ambientLightChance(glm::vec3(constants.ambient));
    RayExchange& ranks = m.exchange();
    m.stageSeconds = {};
    // Leave out what this frame does not need: kernels specialised for its FeatureSet (FeatureSet.h).
    m.features = m.options.specialize ? FeatureSet{scene.features() | m.channelBits |
                                                   (m.exchange().rankCount() > 1 ? gpu::FEATURE_MULTI_RANK : 0u)}
                                      : FeatureSet::all();
    m.selectKernels(m.features.bits);

    FrameStats stats;
    // Bounces a path can take: its interactions plus pass-throughs, plus the one that resolves the last
    // shadow rays. The kernels end paths before this; the bound only guards the loop.
    // (The eyeLight quick look ends every path at its first interaction.)
    const uint32_t pathLength =
        settings.shading == RenderSettings::Shading::EyeLight ? 1u : std::max(1u, settings.maxPathLength);
    const uint32_t maxBounces = pathLength + gpu::PATH_MAX_PASS_THROUGHS + 2;
    // This rank's pixels (all of them with one rank); every rank runs as many passes, waves and bounces as
    // the busiest one, since each exchange needs all ranks. A pass of several samples of each pixel traces
    // the slots k * pixels + pixel of this rank's pixels for each of them (pixelSample in pt_common.glsl).
    if (ranks.rankCount() > 1) ranks.shareRegions(scene.regions());
    const std::vector<PixelRange> owned = ownedPixels(size_, ranks.rank(), ranks.rankCount());
    const uint32_t pixels = size_.x * size_.y;  // fewer than 2^32 (resize)
    uint64_t ownedPixelCount = 0;
    for (const PixelRange& range : owned) ownedPixelCount += range.count;
    const uint32_t passSamples = m.samplesPerPass(pixels, ranks.max(ownedPixelCount), settings.pixelSamples);
    // Several samples a pass fit within pathLimit() (samplesPerPass); one sample of a frame larger than it
    // is traced in waves.
    m.reserve(std::min<uint64_t>(passSamples * ownedPixelCount, m.pathLimit()), uint64_t(passSamples) * pixels);
    constants.passSamples = passSamples;
    constants.latestSample = accumulatedSamples_ + settings.pixelSamples - 1;
    m.uploadFrame(constants, size_);
    m.writeCounters({});
    const auto passWaves = [&](uint32_t samples) {
        std::vector<PixelRange> slots;
        for (uint32_t k = 0; k < samples; ++k)
            for (const PixelRange& range : owned) {
                const uint32_t first = k * pixels + range.first;
                if (!slots.empty() && slots.back().first + slots.back().count == first) slots.back().count += range.count;
                else slots.push_back({first, range.count});
            }
        return packWaves(slots, m.capacity);
    };
    std::vector<Wave> waves = passWaves(passSamples);
    uint64_t waveCount = ranks.max(waves.size());
    m.lengthsOnDevice = ranks.rankCount() == 1;
    const uint32_t sequence = accumulatedFrames_ % 2;
    for (uint32_t s = 0; s < settings.pixelSamples; s += passSamples) {
        const uint32_t samples = std::min(passSamples, settings.pixelSamples - s);
        if (samples != passSamples) {  // the last pass, with fewer (the same on every rank)
            waves = passWaves(samples);
            waveCount = ranks.max(waves.size());
        }
        const uint32_t sampleIndex = accumulatedSamples_;
        m.stratifiedSample = (stratifiedSamples_[sequence] << 1) | sequence;
        stratifiedSamples_[sequence] += samples;
        stats.waves += waveCount;
        for (uint64_t w = 0; w < waveCount; ++w) {
            const Wave* wave = w < waves.size() ? &waves[w] : nullptr;  // this rank may have fewer waves
            if (m.lengthsOnDevice)
                m.traceWave(scene, *wave, sampleIndex, pathLength + 1, maxBounces, stats);
            else
                m.traceWaveAcrossRanks(scene, wave, sampleIndex, maxBounces, stats);
        }
        m.submitTimed([&](VkCommandBuffer cmd) {
            for (const PixelRange& range : owned) {
                gpu::StageParams p = m.params(nullptr);
                p.firstPixel = range.first;
                p.sampleIndex = sampleIndex;
                m.dispatch(cmd, m.accumulate, p, range.count);
            }
            m.mark(cmd, Stage::Accumulate);
            Impl::hostReadBarrier(cmd);
        });
        accumulatedSamples_ += samples;
    }
    ++accumulatedFrames_;
    const gpu::PathCounters c = m.readCounters();
    stats.nonFiniteSamples = c.nonFinite;
    stats.flaggedRays = c.flagged;
    auto sum64 = [](const uint32_t (&words)[2]) { return uint64_t(words[0]) | (uint64_t(words[1]) << 32); };
    stats.realCollisions = sum64(c.realCollisions);
    stats.nullCollisions = sum64(c.nullCollisions);
    stats.ratioCollisions = sum64(c.ratioCollisions);
    stats.parkedMarches = sum64(c.parkedMarches);
    stats.stageSeconds = m.stageSeconds;
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return stats;
}

void PathTracer::readColor(ColorFormat format, void* destination) const {
    if (size_.x == 0) throw std::logic_error("PathTracer::readColor: call resize() first");
    if (format != ColorFormat::Rgba8Unorm && format != ColorFormat::Rgba8Srgb && format != ColorFormat::Rgba32Float)
        throw std::invalid_argument("PathTracer::readColor: unknown color format " + std::to_string(static_cast<uint32_t>(format)));
    Impl& m = *impl_;
    const uint64_t pixels = uint64_t(size_.x) * size_.y;
    if (!m.color) m.color = vk::Buffer(m.context, pixels * sizeof(gpu::vec4), "frame color");
    m.kernelsBuilt();
    gpu::StageParams p = m.params(nullptr);
    p.results = m.color.address();
    p.mode = static_cast<uint32_t>(format);
    m.context.submitAndWait([&](VkCommandBuffer cmd) { m.dispatch(cmd, m.resolve, p, pixels); });
    m.color.download(destination, pixels * (format == ColorFormat::Rgba32Float ? 16 : 4));
}

void PathTracer::readChannel(SurfaceChannel channel, void* destination) const {
    impl_->channels.read(channel, destination);
}

FeatureSet PathTracer::features() const { return impl_->features; }

Traversal PathTracer::traversal() const { return impl_->trace.traversal(); }

std::vector<PipelineCache::Entry> PathTracer::pipelines() const {
    std::vector<PipelineCache::Entry> list = impl_->pipelines.entries();
    for (const PipelineCache::Entry& e : impl_->shadePipelines.entries()) list.push_back(e);
    for (const PipelineCache::Entry& e : impl_->trace.pipelines().entries()) list.push_back(e);
    return list;
}

uint64_t PathTracer::channelBytes() const {
    return impl_->channels.bytes() + (impl_->depth ? uint64_t(size_.x) * size_.y * sizeof(float) : 0);
}

void PathTracer::readDepth(float* destination) const {
    if (!impl_->depth) throw std::logic_error("PathTracer::readDepth: resize() did not ask for a depth channel");
    impl_->depth.download(destination, uint64_t(size_.x) * size_.y * sizeof(float));
}

}  // namespace ripple::core
