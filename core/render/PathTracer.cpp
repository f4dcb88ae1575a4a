// Host side of the wavefront path tracer: frame and queue buffers, and the loop that dispatches the
// pt_*.comp stages. Queue lengths are read back once per bounce (one submit per bounce): the host needs
// them to size the trace dispatches and to stop as soon as every path has ended, and a data-parallel
// version needs the same count for its allreduce.
#include "core/render/PathTracer.h"

#include "core/vk/ComputePipeline.h"
#include "shaders/pt_accumulate.spv.h"
#include "shaders/pt_generate.spv.h"
#include "shaders/pt_resolve.spv.h"
#include "shaders/pt_shade.spv.h"
#include "shaders/pt_shadow_resolve.spv.h"
#include "shaders/pt_surface.spv.h"
#include "shaders/shared/path.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

namespace ripple::core {

namespace {

constexpr uint32_t kWorkgroupSizeConstant = 0;  // layout(local_size_x_id = 0) in pt_common.glsl

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Camera and settings as the kernels read them; throws std::invalid_argument for a camera that cannot
// produce rays.
gpu::FrameConstants frameConstants(const Camera& camera, const RenderSettings& settings) {
    auto reject = [](const std::string& why) { throw std::invalid_argument("PathTracer: camera " + why); };
    if (!finite(camera.position) || !finite(camera.direction) || !finite(camera.up)) reject("position, direction or up is NaN or Inf");
    if (glm::length(camera.direction) == 0.0f) reject("direction is zero");
    if (!(camera.aspect > 0.0f && std::isfinite(camera.aspect))) reject("aspect must be finite and positive");
    const bool ortho = camera.kind == Camera::Kind::Orthographic;
    if (!ortho && camera.kind != Camera::Kind::Perspective) reject("kind is unknown");
    if (ortho && !(camera.height > 0.0f && std::isfinite(camera.height))) reject("height must be finite and positive");
    if (!ortho && !(camera.fovy > 0.0f && camera.fovy < 3.14159f)) reject("fovy must be in (0, pi)");
    for (int i = 0; i < 4; ++i)
        if (!std::isfinite(camera.imageRegion[i])) reject("imageRegion is NaN or Inf");

    const glm::vec3 forward = glm::normalize(camera.direction);
    glm::vec3 right = glm::cross(forward, camera.up);
    if (glm::length(right) < 1e-6f * glm::length(camera.up)) {  // up along the view: any perpendicular will do
        const glm::vec3 a = glm::abs(forward);
        right = glm::cross(forward, a.x < a.y && a.x < a.z ? glm::vec3(1, 0, 0) : a.y < a.z ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1));
    }
    right = glm::normalize(right);
    const glm::vec3 up = glm::cross(right, forward);

    gpu::FrameConstants f{};
    f.cameraPosition = gpu::vec4(camera.position, std::bit_cast<float>(ortho ? gpu::CAMERA_ORTHOGRAPHIC : gpu::CAMERA_PERSPECTIVE));
    f.cameraForward = gpu::vec4(forward, ortho ? camera.height : std::tan(0.5f * camera.fovy));
    f.cameraRight = gpu::vec4(right, camera.aspect);
    f.cameraUp = gpu::vec4(up, 0.0f);
    f.imageRegion = camera.imageRegion;
    f.background = settings.background;
    f.ambient = gpu::vec4(settings.ambientColor * settings.ambientRadiance, 0.0f);
    f.maxPathLength = std::max(1u, settings.maxPathLength);
    f.seed = settings.seed;
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
    vk::ComputePipeline generate, surface, shade, shadowResolve, accumulate, resolve;
    vk::Buffer frame, counters;                                     // FrameConstants, PathCounters
    vk::Buffer sampleRadiance, accumulation, sampleCount, depth, color;  // per pixel
    Queue queues[2];
    int current = 0;                                                // the queue the next bounce consumes
    vk::Buffer hits, surfaces, shadowRays, shadowRequests, occlusion; // per path in flight
    uint32_t capacity = 0;

    Impl(const vk::Context& ctx, const TraceOptions& traceOptions, const PathTracerOptions& opts)
        : context(ctx), options(opts), trace(ctx, traceOptions) {
        if (options.queueCapacity == 0 || options.workgroupSize == 0)
            throw std::invalid_argument("PathTracerOptions: queueCapacity and workgroupSize must be positive");
        const vk::SpecializationConstant constants[] = {{kWorkgroupSizeConstant, options.workgroupSize}};
        const auto bytes = static_cast<uint32_t>(sizeof(gpu::StageParams));
        generate = vk::ComputePipeline(ctx, shaders::pt_generate, "pt_generate", bytes, constants);
        surface = vk::ComputePipeline(ctx, shaders::pt_surface, "pt_surface", bytes, constants);
        shade = vk::ComputePipeline(ctx, shaders::pt_shade, "pt_shade", bytes, constants);
        shadowResolve = vk::ComputePipeline(ctx, shaders::pt_shadow_resolve, "pt_shadow_resolve", bytes, constants);
        accumulate = vk::ComputePipeline(ctx, shaders::pt_accumulate, "pt_accumulate", bytes, constants);
        resolve = vk::ComputePipeline(ctx, shaders::pt_resolve, "pt_resolve", bytes, constants);
        frame = vk::Buffer(ctx, sizeof(gpu::FrameConstants), "path tracer frame constants");
        // Host-visible on every device: the host reads the queue counts after each bounce.
        counters = vk::Buffer(ctx, sizeof(gpu::PathCounters), "path tracer counters", 0, vk::Buffer::Placement::HostStaging);
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

    // One stage over `count` items, in as many dispatches as the device's workgroup-count limit needs;
    // firstPixel advances with each one (only the per-pixel stages get more than one: queues are capped
    // to one dispatch in resize).
    void dispatch(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline, gpu::StageParams p, uint64_t count) {
        vk::computeBarrier(cmd);
        pipeline.bind(cmd);
        const uint64_t perDispatch = uint64_t(context.properties().limits.maxComputeWorkGroupCount[0]) * options.workgroupSize;
        for (uint64_t done = 0; done < count; done += perDispatch) {
            gpu::StageParams chunk = p;
            chunk.count = static_cast<uint32_t>(std::min(perDispatch, count - done));
            chunk.firstPixel = p.firstPixel + static_cast<uint32_t>(done);
            pipeline.pushConstants(cmd, &chunk, sizeof(chunk));
            vkCmdDispatch(cmd, (chunk.count + options.workgroupSize - 1) / options.workgroupSize, 1, 1);
        }
    }

    void generateRays(VkCommandBuffer cmd, uint64_t firstPixel, uint32_t count, uint32_t sampleIndex) {
        gpu::StageParams p = params(nullptr);
        p.paths = queues[current].paths.address();
        p.rays = queues[current].rays.address();
        p.firstPixel = static_cast<uint32_t>(firstPixel);
        p.sampleIndex = sampleIndex;
        dispatch(cmd, generate, p, count);
    }

    // Any-hit for the shadow rays of the previous bounce, then their contributions.
    void occlude(VkCommandBuffer cmd, const Scene& scene, uint32_t count) {
        if (count == 0) return;
        vk::computeBarrier(cmd);
        trace.traceAny(cmd, scene, shadowRays, occlusion, count);
        gpu::StageParams p = params(&scene);
        p.shadowRequests = shadowRequests.address();
        p.results = occlusion.address();
        dispatch(cmd, shadowResolve, p, count);
    }

    // Closest hit for the current queue, the surface at each hit, then shading into the other queue and the
    // shadow queue.
    void traceAndShade(VkCommandBuffer cmd, const Scene& scene, uint32_t count, uint32_t bounce, uint32_t sampleIndex) {
        if (count == 0) return;
        const Queue& in = queues[current];
        const Queue& out = queues[1 - current];
        vk::computeBarrier(cmd);
        trace.traceClosest(cmd, scene, in.rays, hits, count);
        gpu::StageParams p = params(&scene);
        p.paths = in.paths.address();
        p.rays = in.rays.address();
        p.hits = hits.address();
        p.surfaces = surfaces.address();
        dispatch(cmd, surface, p, count);
        p.nextPaths = out.paths.address();
        p.nextRays = out.rays.address();
        p.shadowRays = shadowRays.address();
        p.shadowRequests = shadowRequests.address();
        p.bounce = bounce;
        p.sampleIndex = sampleIndex;
        dispatch(cmd, shade, p, count);
    }

    // After a bounce: the lengths of the queues it filled, which become the ones to consume next.
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

void PathTracer::resize(glm::uvec2 size, bool wantDepth) {
    const uint64_t pixels = uint64_t(size.x) * size.y;
    if (pixels == 0 || pixels > UINT32_MAX)
        throw std::invalid_argument("PathTracer::resize: " + std::to_string(size.x) + "x" + std::to_string(size.y) +
                                    " pixels (need at least one, and fewer than 2^32)");
    Impl& m = *impl_;
    const vk::Context& ctx = m.context;
    m.sampleRadiance = vk::Buffer(ctx, pixels * sizeof(gpu::vec4), "frame sample radiance");
    m.accumulation = vk::Buffer(ctx, pixels * sizeof(gpu::vec4), "frame accumulation");
    m.sampleCount = vk::Buffer(ctx, pixels * sizeof(uint32_t), "frame sample count");
    m.depth = wantDepth ? vk::Buffer(ctx, pixels * sizeof(float), "frame depth") : vk::Buffer();
    m.color = vk::Buffer();  // allocated by the first readColor
    // Queue stages index their queue by invocation, so one dispatch must cover a whole queue.
    const uint64_t oneDispatch = uint64_t(ctx.properties().limits.maxComputeWorkGroupCount[0]) * m.options.workgroupSize;
    m.capacity = static_cast<uint32_t>(std::min<uint64_t>({pixels, m.options.queueCapacity, oneDispatch}));
    for (int q = 0; q < 2; ++q) {
        m.queues[q].paths = vk::Buffer(ctx, uint64_t(m.capacity) * sizeof(gpu::PathState), "path queue " + std::to_string(q) + " states");
        m.queues[q].rays = vk::Buffer(ctx, uint64_t(m.capacity) * sizeof(gpu::Ray), "path queue " + std::to_string(q) + " rays");
    }
    m.hits = vk::Buffer(ctx, uint64_t(m.capacity) * sizeof(gpu::Hit), "path hits");
    m.surfaces = vk::Buffer(ctx, uint64_t(m.capacity) * sizeof(gpu::SurfaceRecord), "path surface records");
    m.shadowRays = vk::Buffer(ctx, uint64_t(m.capacity) * sizeof(gpu::Ray), "shadow rays");
    m.shadowRequests = vk::Buffer(ctx, uint64_t(m.capacity) * sizeof(gpu::ShadowRequest), "shadow requests");
    m.occlusion = vk::Buffer(ctx, uint64_t(m.capacity) * sizeof(uint32_t), "shadow occlusion");
    size_ = size;
    m.uploadFrame(gpu::FrameConstants{}, size);
    resetAccumulation();
}

void PathTracer::resetAccumulation() {
    accumulatedSamples_ = 0;
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
    m.uploadFrame(frameConstants(camera, settings), size_);
    m.writeCounters({});

    FrameStats stats;
    const uint64_t pixels = uint64_t(size_.x) * size_.y;
    // Bounces a path can take: its interactions plus pass-throughs, plus the one that resolves the last
    // shadow rays. The kernels end paths before this; the bound only guards the loop.
    const uint32_t maxBounces = std::max(1u, settings.maxPathLength) + gpu::PATH_MAX_PASS_THROUGHS + 2;
    for (uint32_t s = 0; s < settings.pixelSamples; ++s) {
        const uint32_t sampleIndex = accumulatedSamples_;
        for (uint64_t first = 0; first < pixels; first += m.capacity) {
            uint32_t paths = static_cast<uint32_t>(std::min<uint64_t>(m.capacity, pixels - first)), shadows = 0;
            for (uint32_t bounce = 0; (paths > 0 || shadows > 0) && bounce <= maxBounces; ++bounce) {
                m.context.submitAndWait([&](VkCommandBuffer cmd) {
                    if (bounce == 0) m.generateRays(cmd, first, paths, sampleIndex);
                    m.occlude(cmd, scene, shadows);
                    m.traceAndShade(cmd, scene, paths, bounce, sampleIndex);
                    Impl::hostReadBarrier(cmd);
                });
                stats.raysTraced += paths;
                stats.shadowRays += shadows;
                std::tie(paths, shadows) = m.takeQueueCounts();
            }
        }
        m.context.submitAndWait([&](VkCommandBuffer cmd) {
            m.dispatch(cmd, m.accumulate, m.params(nullptr), pixels);
            Impl::hostReadBarrier(cmd);
        });
        ++accumulatedSamples_;
    }
    const gpu::PathCounters c = m.readCounters();
    stats.nonFiniteSamples = c.nonFinite;
    stats.flaggedRays = c.flagged;
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
    gpu::StageParams p = m.params(nullptr);
    p.results = m.color.address();
    p.mode = static_cast<uint32_t>(format);
    m.context.submitAndWait([&](VkCommandBuffer cmd) { m.dispatch(cmd, m.resolve, p, pixels); });
    m.color.download(destination, pixels * (format == ColorFormat::Rgba32Float ? 16 : 4));
}

void PathTracer::readDepth(float* destination) const {
    if (!impl_->depth) throw std::logic_error("PathTracer::readDepth: resize() did not ask for a depth channel");
    impl_->depth.download(destination, uint64_t(size_.x) * size_.y * sizeof(float));
}

}  // namespace ripple::core
