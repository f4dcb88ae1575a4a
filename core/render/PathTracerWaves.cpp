// How a frame's passes split into waves, the stages of a wave (pt_*.comp) and the bounce loops that run
// them, on one rank or across several.
// With one rank the queue lengths stay on the device (pt_queue_advance sizes the next bounce's indirect
// dispatches), so a wave's bounces are one submission and the host only checks once, after the bounces a
// path without pass-throughs can take, whether any path remains. With several ranks the host reads the
// lengths after every bounce: the exchange and its allreduce need them.
#include "core/render/PathTracerImpl.h"

#include <algorithm>
#include <stdexcept>
#include <tuple>
#include <vector>

namespace ripple::core {

// How many of each pixel's samples a pass of this frame traces together, the same on every rank: as many
// as keep the busiest rank's pass (`busiest` pixels a sample) within options.packedWavePaths and one
// dispatch, and the pass's sample slots (all pixels times the samples) within the queue capacity.
uint32_t PathTracer::Impl::samplesPerPass(uint64_t pixels, uint64_t busiest, uint32_t pixelSamples) const {
    const uint64_t paths = std::min<uint64_t>(options.packedWavePaths, pathLimit());
    if (busiest == 0 || busiest * 2 > paths) return 1;
    const uint64_t samples = std::min<uint64_t>({pixelSamples, paths / busiest, options.queueCapacity / pixels});
    return static_cast<uint32_t>(std::max<uint64_t>(samples, 1));
}

// The waves of a pass that traces `samples` samples of each of this rank's pixels (`owned`), at the slots
// k * pixels + pixel (pixelSample in pt_common.glsl).
std::vector<Wave> PathTracer::Impl::passWaves(const std::vector<PixelRange>& owned, uint32_t pixels,
                                              uint32_t samples) const {
    std::vector<PixelRange> slots;
    for (uint32_t k = 0; k < samples; ++k)
        for (const PixelRange& range : owned) {
            const uint32_t first = k * pixels + range.first;
            if (!slots.empty() && slots.back().first + slots.back().count == first) slots.back().count += range.count;
            else slots.push_back({first, range.count});
        }
    return packWaves(slots, capacity);
}

// One rank, between bounces: what the bounce appended becomes the lengths the next one consumes (the
// caller swaps `current`).
void PathTracer::Impl::advanceQueueLengths(VkCommandBuffer cmd) {
    vk::computeBarrier(cmd);
    queueAdvance.bind(cmd);
    const gpu::QueueAdvanceParams p{counters.address(), capacity, options.workgroupSize, trace.options().workgroupSize, 0};
    queueAdvance.pushConstants(cmd, &p, sizeof(p));
    queueAdvance.dispatch(cmd, 1);
    mark(cmd, Stage::QueueAdvance);
}

void PathTracer::Impl::generateRays(VkCommandBuffer cmd, const Wave& wave, uint32_t sampleIndex) {
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

// Any-hit for the shadow rays of the previous bounce; their contributions follow the exchange.
// (With lengths on the device the host's counts below are not used.)
void PathTracer::Impl::occlude(VkCommandBuffer cmd, const Scene& scene, uint32_t count) {
    if (count == 0 && !lengthsOnDevice) return;
    vk::computeBarrier(cmd);
    if (lengthsOnDevice) trace.traceAny(cmd, scene, shadowRays, occlusion, deviceRayCount(gpu::COUNT_SHADOW_QUEUE));
    else trace.traceAny(cmd, scene, shadowRays, occlusion, count);
    mark(cmd, Stage::TraceAny);
}

void PathTracer::Impl::resolveShadows(VkCommandBuffer cmd, const Scene& scene, uint32_t count, uint32_t bounce,
                                      uint32_t sampleIndex) {
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
void PathTracer::Impl::traceAndShade(VkCommandBuffer cmd, const Scene& scene, uint32_t count, uint32_t bounce,
                                     uint32_t sampleIndex) {
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
void PathTracer::Impl::shadePaths(VkCommandBuffer cmd, const Scene& scene, uint32_t count, uint32_t bounce,
                                  uint32_t sampleIndex) {
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
void PathTracer::Impl::exchangeRays(const Scene& scene, uint32_t paths, uint32_t shadows, uint32_t bounce,
                                    uint32_t sampleIndex) {
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
void PathTracer::Impl::traceWave(const Scene& scene, const Wave& wave, uint32_t sampleIndex, uint32_t firstBatch,
                                 uint32_t maxBounces, FrameStats& stats) {
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
void PathTracer::Impl::traceWaveAcrossRanks(const Scene& scene, const Wave* wave, uint32_t sampleIndex,
                                            uint32_t maxBounces, FrameStats& stats) {
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
std::pair<uint32_t, uint32_t> PathTracer::Impl::takeQueueCounts() {
    gpu::PathCounters c = readCounters();
    const std::pair<uint32_t, uint32_t> counts{std::min(c.nextPaths, capacity), std::min(c.shadowRays, capacity)};
    c.nextPaths = c.shadowRays = 0;
    writeCounters(c);
    current = 1 - current;
    return counts;
}

// After a pass's waves: its samples into the accumulation of this rank's pixels.
void PathTracer::Impl::accumulatePass(const std::vector<PixelRange>& owned, uint32_t sampleIndex) {
    submitTimed([&](VkCommandBuffer cmd) {
        for (const PixelRange& range : owned) {
            gpu::StageParams p = params(nullptr);
            p.firstPixel = range.first;
            p.sampleIndex = sampleIndex;
            dispatch(cmd, accumulate, p, range.count);
        }
        mark(cmd, Stage::Accumulate);
        hostReadBarrier(cmd);
    });
}

}  // namespace ripple::core
