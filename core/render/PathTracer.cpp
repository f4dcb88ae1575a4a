// The path tracer's public side: the frame's buffers (resize), and render(), the frame as passes of waves
// that accumulate. The kernels and buffers are in PathTracerKernels.cpp, the stages in PathTracerWaves.cpp.
#include "core/render/PathTracer.h"

#include "core/render/CameraRays.h"
#include "core/render/PathTracerImpl.h"
#include "core/render/PixelTiles.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ripple::core {

namespace {

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
    std::vector<Wave> waves = m.passWaves(owned, pixels, passSamples);
    uint64_t waveCount = ranks.max(waves.size());
    m.lengthsOnDevice = ranks.rankCount() == 1;
    const uint32_t sequence = accumulatedFrames_ % 2;
    for (uint32_t s = 0; s < settings.pixelSamples; s += passSamples) {
        const uint32_t samples = std::min(passSamples, settings.pixelSamples - s);
        if (samples != passSamples) {  // the last pass, with fewer (the same on every rank)
            waves = m.passWaves(owned, pixels, samples);
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
        m.accumulatePass(owned, sampleIndex);
        accumulatedSamples_ += samples;
    }
    ++accumulatedFrames_;
    m.readFrameCounters(stats);
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
