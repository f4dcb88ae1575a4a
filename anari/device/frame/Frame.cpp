// Frame parameters, the asynchronous render on a worker thread, and channel mapping (see Frame.h).
#include "anari/device/frame/Frame.h"

#include "anari/device/frame/DataParallelFrame.h"
#include "anari/device/object/DeviceState.h"
#include "mpi/FrameGather.h"
#include "mpi/LightGather.h"
#include "core/vk/Context.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <exception>
#include <string>
#include <utility>

namespace ripple::device {
namespace {

// One Vulkan context serves every frame of a device, and its queue and one-shot submission are not
// thread-safe: frames take turns on the GPU.
std::mutex& gpuMutex() {
    static std::mutex mutex;
    return mutex;
}

core::ColorFormat colorFormatOf(ANARIDataType type) {
    switch (type) {
        case ANARI_UFIXED8_RGBA_SRGB: return core::ColorFormat::Rgba8Srgb;
        case ANARI_FLOAT32_VEC4: return core::ColorFormat::Rgba32Float;
        default: return core::ColorFormat::Rgba8Unorm;
    }
}

bool channelIs(std::string_view channel, std::string_view name) {
    // ANARI 1.0 names channels "channel.color"; earlier drafts and some applications say "color".
    return channel == name || channel == std::string("channel.").append(name);
}

}  // namespace

Frame::Frame(DeviceState& state) : Object(state, ANARI_FRAME, ""), globalIndex_(state.nextFrameIndex()) {}

Frame::~Frame() {
    waitForWorker();
}

void Frame::commit() {
    waitForWorker();  // the worker reads nothing committed, but a new size must not race its readback
    world_ = ObjectRef<World>(dynamic_cast<World*>(getObject("world", ANARI_WORLD)));
    camera_ = ObjectRef<Camera>(dynamic_cast<Camera*>(getObject("camera", ANARI_CAMERA)));
    renderer_ = ObjectRef<Renderer>(dynamic_cast<Renderer*>(getObject("renderer", ANARI_RENDERER)));

    // 16384 is far beyond what lavapipe renders interactively, and keeps width * height * 16 in range.
    size_ = get<glm::uvec2>("size", glm::uvec2(0));
    if (size_.x == 0 || size_.y == 0 || size_.x > 16384 || size_.y > 16384)
        invalidate(has("size") ? "parameter 'size' must be between 1x1 and 16384x16384"
                               : "missing required parameter 'size'");

    auto pullChannel = [&](const char* name) -> ANARIDataType {
        const Parameter* parameter = findParameter(name);
        if (!parameter) return ANARI_UNKNOWN;
        if (parameter->type != ANARI_DATA_TYPE) {
            reportError(std::string("parameter '") + name + "' must be an ANARI_DATA_TYPE; channel disabled");
            return ANARI_UNKNOWN;
        }
        ANARIDataType type = ANARI_UNKNOWN;
        std::memcpy(&type, parameter->bytes.data(), sizeof(type));
        return type;
    };
    colorType_ = pullChannel("channel.color");
    if (colorType_ != ANARI_UNKNOWN && colorType_ != ANARI_UFIXED8_VEC4 && colorType_ != ANARI_UFIXED8_RGBA_SRGB &&
        colorType_ != ANARI_FLOAT32_VEC4) {
        reportError(std::string("parameter 'channel.color' is ") + ripple_anari::typeName(colorType_) +
                    "; supported are UFIXED8_VEC4, UFIXED8_RGBA_SRGB and FLOAT32_VEC4. Channel disabled");
        colorType_ = ANARI_UNKNOWN;
    }
    // Each optional channel has one supported type; any other is reported and the channel disabled.
    auto pullTypedChannel = [&](const char* name, ANARIDataType supported) {
        const ANARIDataType type = pullChannel(name);
        if (type != ANARI_UNKNOWN && type != supported)
            reportError(std::string("parameter '") + name + "' is " + ripple_anari::typeName(type) + "; supported is " +
                        ripple_anari::typeName(supported) + ". Channel disabled");
        return type == supported;
    };
    depth_ = pullTypedChannel("channel.depth", ANARI_FLOAT32);
    channels_ = core::FrameChannels{};
    channels_.depth = depth_;
    channels_.albedo = pullTypedChannel("channel.albedo", ANARI_FLOAT32_VEC3);
    channels_.normal = pullTypedChannel("channel.normal", ANARI_FLOAT32_VEC3);
    channels_.primitiveId = pullTypedChannel("channel.primitiveId", ANARI_UINT32);
    channels_.objectId = pullTypedChannel("channel.objectId", ANARI_UINT32);
    channels_.instanceId = pullTypedChannel("channel.instanceId", ANARI_UINT32);
}

// Collective: false (reported on every rank) unless all ranks can render the same frame together.
bool Frame::prepareDistributed(bool renderable, bool& restart) {
    FrameIdentity mine;
    mine.frameIndex = globalIndex_;
    mine.worldIndex = world_ ? world_->globalIndex() : ~0ull;
    mine.size = size_;
    mine.renderable = renderable;
    if (renderable) {
        mine.camera = camera_->camera(float(size_.x) / float(size_.y));
        mine.pixelSamples = renderer_->settings().pixelSamples;
        mine.maxPathLength = renderer_->settings().maxPathLength;
    }
    restart = false;
    if (const std::string why = ranksDisagree(state().communicator(), mine); !why.empty()) {
        reportError("cannot render (data-parallel): " + why);
        return false;
    }
    return true;
}

std::string Frame::whyNotRenderable() const {
    if (!isValid()) return "the frame's parameters are invalid (reported at commit)";
    if (!world_) return "no usable 'world'";
    if (!camera_) return "no usable 'camera'";
    if (!renderer_) return "no usable 'renderer'";
    if (!world_->isValid()) return "its world is invalid";
    if (!camera_->isValid()) return "its camera is invalid";
    if (!renderer_->isValid()) return "its renderer is invalid";
    return {};
}

void Frame::renderFrame() {
    waitForWorker();
    discarded_ = false;
    const bool distributed = state().communicator().distributed();
    bool restart = false;
    if (distributed && !prepareDistributed(whyNotRenderable().empty(), restart)) return;
    if (const std::string why = whyNotRenderable(); !why.empty()) {
        reportError("cannot render: " + why);
        return;
    }

    Job job;
    job.size = size_;
    job.colorType = colorType_;
    job.depth = depth_;
    job.channels = channels_;
    job.camera = camera_->camera(float(size_.x) / float(size_.y));
    job.settings = renderer_->settings();
    // Scene sync runs here, on the application's thread: the objects are only ever read on it.
    const bool sceneChanged = sync_.update(*world_);
    const bool cameraChanged = camera_.get() != renderedCamera_ || camera_->lastCommitted() != renderedCameraStamp_;
    const bool rendererChanged =
        renderer_.get() != renderedRenderer_ || renderer_->lastCommitted() != renderedRendererStamp_;
    job.restartAccumulation = sceneChanged || cameraChanged || rendererChanged;
    if (distributed) {  // lights of every rank, the world's radius, and a restart anywhere restarts all
        const mpi::Communicator& ranks = state().communicator();
        bvh::Aabb bounds = worldBounds(*world_);
        ranks.min(std::span<float>(&bounds.lo.x, 3));
        ranks.max(std::span<float>(&bounds.hi.x, 3));
        const float radius = bounds.empty() ? 1.0f : 0.5f * glm::length(bounds.hi - bounds.lo);
        const glm::vec3 largest = glm::max(glm::abs(bounds.lo), glm::abs(bounds.hi));
        const float magnitude = bounds.empty() ? 0.0f : std::max(largest.x, std::max(largest.y, largest.z));
        restart = sync_.setLights(mpi::gatherLights(ranks, sync_.localLights()), radius, magnitude) ||
                  job.restartAccumulation;
        job.restartAccumulation = ranks.max(restart ? 1 : 0) > 0;
    }
    renderedCamera_ = camera_.get();
    renderedCameraStamp_ = camera_->lastCommitted();
    renderedRenderer_ = renderer_.get();
    renderedRendererStamp_ = renderer_->lastCommitted();

    finished_ = false;
    state().beginWork();
    if (distributed) return run(job);
    try {
        worker_ = std::thread([this, job] { run(job); });
    } catch (...) {
        finished_ = true;
        state().endWork();
        throw;
    }
}

void Frame::run(const Job& job) {
    const auto start = std::chrono::steady_clock::now();
    try {
        std::lock_guard gpu(gpuMutex());
        vk::Context& context = state().vulkan();
        const uint64_t validationBefore = context.validationMessageCount();
        if (!tracer_) {
            core::PathTracerOptions options;
            if (state().communicator().distributed()) {
                ring_ = std::make_unique<mpi::RingExchange>(state().communicator());
                options.exchange = ring_.get();
            }
            tracer_ = std::make_unique<core::PathTracer>(context, core::TraceOptions{}, options);
        }

        bool rebuilt = false;
        const core::Scene& scene =
            ring_ ? sceneWithSharedEmitters(ring_->communicator(), sync_, context, rebuilt) : sync_.scene(context, rebuilt);
        if (rebuilt)
            for (const std::string& message : scene.report().messages) reportWarning("scene: " + message);

        // Resizing clears the accumulation as well.
        if (tracer_->size() != job.size || core::channelFeatures(tracerChannels_) != core::channelFeatures(job.channels)) {
            tracer_->resize(job.size, job.channels);
            tracerChannels_ = job.channels;
        } else if (job.restartAccumulation)
            tracer_->resetAccumulation();

        if (!discarded_) {
            if (ring_) ring_->resetStats();
            const core::FrameStats stats = tracer_->render(scene, job.camera, job.settings);
            Results results;
            results.size = job.size;
            results.colorType = job.colorType;
            const size_t pixels = size_t(job.size.x) * job.size.y;
            if (job.colorType != ANARI_UNKNOWN) {
                results.color.resize(pixels * (job.colorType == ANARI_FLOAT32_VEC4 ? 16 : 4));
                tracer_->readColor(colorFormatOf(job.colorType), results.color.data());
            }
            if (job.depth) {
                results.depth.resize(pixels);
                tracer_->readDepth(results.depth.data());
            }
            readSurfaceChannels(job, pixels, results);
            if (ring_) {  // rank 0 assembles every rank's pixel bands; the others keep an undefined frame
                const mpi::Communicator& ranks = ring_->communicator();
                if (!results.color.empty())
                    mpi::gatherFrame(ranks, job.size, results.color.size() / pixels, results.color.data());
                if (!results.depth.empty()) mpi::gatherFrame(ranks, job.size, sizeof(float), results.depth.data());
            }
            results.numSamples = tracer_->accumulatedSamples();
            const double rays = double(stats.raysTraced + stats.shadowRays);
            results.raysPerSecond = stats.seconds > 0.0 ? float(rays / stats.seconds) : 0.0f;
            results.sceneBuilds = sync_.builds();
            results.blasBuilt = scene.report().blasBuilt;
            results.blasReused = scene.report().blasReused;
            results.sceneBytes = scene.report().gpuBytes;
            if (ring_) {
                results.raysSent = ring_->stats().raysSent;
                results.bytesSent = ring_->stats().bytesSent;
            }
            results.duration = std::chrono::duration<float>(std::chrono::steady_clock::now() - start).count();
            std::lock_guard lock(resultsMutex_);
            results_ = std::move(results);
        }
        // Validation runs inside the device, where the application cannot see it: say so through the
        // status callback, as an error, so tests fail on it.
        if (context.validationMessageCount() != validationBefore)
            reportError("Vulkan validation: " + context.lastValidationMessage());
    } catch (const std::exception& error) {
        reportError(std::string("rendering failed: ") + error.what());
        // The other ranks wait in the exchange for this one: end them all, with the message, never hang.
        if (ring_) ring_->communicator().abort(std::string("rendering failed: ") + error.what());
    } catch (...) {
        reportError("rendering failed: unknown exception");
        if (ring_) ring_->communicator().abort("rendering failed: unknown exception");
    }
    finished_ = true;
    state().endWork();
}

void Frame::readSurfaceChannels(const Job& job, size_t pixels, Results& results) {
    using core::SurfaceChannel;
    if (job.channels.albedo) {
        results.albedo.resize(3 * pixels);
        tracer_->readChannel(SurfaceChannel::Albedo, results.albedo.data());
    }
    if (job.channels.normal) {
        results.normal.resize(3 * pixels);
        tracer_->readChannel(SurfaceChannel::Normal, results.normal.data());
    }
    const std::pair<bool, SurfaceChannel> ids[] = {{job.channels.primitiveId, SurfaceChannel::PrimitiveId},
                                                   {job.channels.objectId, SurfaceChannel::ObjectId},
                                                   {job.channels.instanceId, SurfaceChannel::InstanceId}};
    for (int i = 0; i < 3; ++i) {
        if (!ids[i].first) continue;
        results.ids[i].resize(pixels);
        tracer_->readChannel(ids[i].second, results.ids[i].data());
    }
}

void Frame::waitForWorker() {
    if (worker_.joinable()) worker_.join();
}

bool Frame::ready(bool wait) {
    if (wait || finished_) waitForWorker();
    return !worker_.joinable();
}

void Frame::discard() {
    // A render already on the GPU cannot be interrupted; one that has not started yet is skipped.
    discarded_ = true;
}

const void* Frame::map(std::string_view channel, uint32_t* width, uint32_t* height, ANARIDataType* pixelType) {
    waitForWorker();
    const void* pixels = nullptr;
    ANARIDataType type = ANARI_UNKNOWN;
    if (channelIs(channel, "color") && !results_.color.empty()) {
        pixels = results_.color.data();
        type = results_.colorType;
    } else if (channelIs(channel, "depth") && !results_.depth.empty()) {
        pixels = results_.depth.data();
        type = ANARI_FLOAT32;
    } else if (channelIs(channel, "albedo") && !results_.albedo.empty()) {
        pixels = results_.albedo.data();
        type = ANARI_FLOAT32_VEC3;
    } else if (channelIs(channel, "normal") && !results_.normal.empty()) {
        pixels = results_.normal.data();
        type = ANARI_FLOAT32_VEC3;
    } else if (channelIs(channel, "primitiveId") && !results_.ids[0].empty()) {
        pixels = results_.ids[0].data();
        type = ANARI_UINT32;
    } else if (channelIs(channel, "objectId") && !results_.ids[1].empty()) {
        pixels = results_.ids[1].data();
        type = ANARI_UINT32;
    } else if (channelIs(channel, "instanceId") && !results_.ids[2].empty()) {
        pixels = results_.ids[2].data();
        type = ANARI_UINT32;
    } else {
        reportError("channel '" + std::string(channel) +
                    "' cannot be mapped: it was not enabled (channel.color, .depth, .albedo, .normal, .primitiveId, "
                    ".objectId, .instanceId), or nothing was rendered");
    }
    if (width) *width = pixels ? results_.size.x : 0;
    if (height) *height = pixels ? results_.size.y : 0;
    if (pixelType) *pixelType = type;
    return pixels;
}

void Frame::unmap(std::string_view) {}  // the mapped memory is the frame's own until the next render

bool Frame::getProperty(std::string_view name, ANARIDataType type, void* mem, uint64_t size, bool wait) {
    if (wait) waitForWorker();
    std::lock_guard lock(resultsMutex_);
    if (name == "duration" && type == ANARI_FLOAT32 && size >= sizeof(float)) {
        std::memcpy(mem, &results_.duration, sizeof(float));
        return true;
    }
    if (name == "ripple.raysPerSecond" && type == ANARI_FLOAT32 && size >= sizeof(float)) {
        std::memcpy(mem, &results_.raysPerSecond, sizeof(float));
        return true;
    }
    if (name == "numSamples" && type == ANARI_UINT32 && size >= sizeof(uint32_t)) {
        std::memcpy(mem, &results_.numSamples, sizeof(uint32_t));
        return true;
    }
    const std::pair<std::string_view, const uint64_t*> counters[] = {{"ripple.sceneBuilds", &results_.sceneBuilds},
                                                                     {"ripple.blasBuilt", &results_.blasBuilt},
                                                                     {"ripple.blasReused", &results_.blasReused},
                                                                     {"ripple.raysSent", &results_.raysSent},
                                                                     {"ripple.bytesSent", &results_.bytesSent},
                                                                     {"ripple.sceneBytes", &results_.sceneBytes}};
    for (const auto& [counter, value] : counters) {
        if (name == counter && type == ANARI_UINT64 && size >= sizeof(uint64_t)) {
            std::memcpy(mem, value, sizeof(uint64_t));
            return true;
        }
    }
    return Object::getProperty(name, type, mem, size, wait);
}

}  // namespace ripple::device
