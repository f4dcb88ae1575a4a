// Frame parameters, the asynchronous render on a worker thread, and channel mapping (see Frame.h).
#include "anari/device/frame/Frame.h"

#include "anari/device/object/DeviceState.h"
#include "core/vk/Context.h"

#include <algorithm>
#include <chrono>
#include <cmath>
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

    // 16384 is far beyond what lavapipe renders interactively; whether a size fits in memory is checked at
    // render (FrameMemory.h), once the channels and the device are known.
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

    // KHR_FRAME_ACCUMULATION: on by default (frames add samples while nothing changes); off, every
    // anariRenderFrame starts over.
    accumulation_ = get<bool>("accumulation", true);

    // KHR_DATA_PARALLEL_MPI: the frame may name the application's communicator (the device's one, which
    // must be given before the first collective call).
    if (const Parameter* communicator = findParameter("mpiCommunicator")) {
        const void* address = nullptr;
        if (communicator->type == ANARI_VOID_POINTER) {
            std::memcpy(&address, communicator->bytes.data(), sizeof(address));
            state().setCommunicatorHandle(address);
        } else {
            reportError(std::string("parameter 'mpiCommunicator' is ") + ripple_anari::typeName(communicator->type) +
                        "; expected ANARI_VOID_POINTER (the address of an MPI_Comm). Ignored");
        }
    }

    // KHR_FRAME_COMPLETION_CALLBACK: called once per render, when its results can be mapped.
    completion_ = nullptr;
    if (const Parameter* callback = findParameter("frameCompletionCallback")) {
        if (callback->type == ANARI_FRAME_COMPLETION_CALLBACK)
            std::memcpy(&completion_, callback->bytes.data(), sizeof(completion_));
        else
            reportError(std::string("parameter 'frameCompletionCallback' is ") + ripple_anari::typeName(callback->type) +
                        "; expected ANARI_FRAME_COMPLETION_CALLBACK. No callback");
    }
    completionUserData_ = nullptr;
    if (const Parameter* user = findParameter("frameCompletionCallbackUserData")) {
        if (user->type == ANARI_VOID_POINTER)
            std::memcpy(&completionUserData_, user->bytes.data(), sizeof(completionUserData_));
        else
            reportError(std::string("parameter 'frameCompletionCallbackUserData' is ") +
                        ripple_anari::typeName(user->type) + "; expected ANARI_VOID_POINTER. Passing NULL");
    }
}

FrameFingerprint Frame::fingerprint(bool renderable) const {
    using F = FrameFingerprint;
    FrameFingerprint mine;
    mine.fields[F::FrameIndex] = globalIndex_;
    mine.fields[F::WorldIndex] = world_ ? world_->globalIndex() : ~0ull;
    mine.fields[F::Size] = uint64_t(size_.x) << 32 | size_.y;
    mine.fields[F::Channels] = uint64_t(uint32_t(colorType_)) << 32 | core::channelFeatures(channels_);
    if (!renderable) return mine;  // camera and renderer may be missing: Renderable stays 0
    mine.fields[F::Renderable] = 1;
    mine.fields[F::RayExchange] = uint64_t(state().rayExchange());
    const core::RenderSettings& settings = renderer_->settings();
    mine.fields[F::PixelSamples] = settings.pixelSamples;
    mine.fields[F::MaxPathLength] = settings.maxPathLength;
    const std::string& rendererType = renderer_->subtype();
    mine.fields[F::Renderer] = fingerprintHash(&settings, sizeof(settings), fingerprintHash(rendererType.data(), rendererType.size()));
    const core::Camera camera = camera_->camera(float(size_.x) / float(size_.y));
    const std::string& cameraType = camera_->subtype();
    mine.fields[F::Camera] = fingerprintHash(&camera, sizeof(camera), fingerprintHash(cameraType.data(), cameraType.size()));
    return mine;
}

std::string Frame::whyNotRenderable() {
    if (!isValid()) return "the frame's parameters are invalid (reported at commit)";
    if (!world_) return "no usable 'world'";
    if (!camera_) return "no usable 'camera'";
    if (!renderer_) return "no usable 'renderer'";
    if (!world_->isValid()) return "its world is invalid";
    if (!camera_->isValid()) return "its camera is invalid";
    if (!renderer_->isValid()) return "its renderer is invalid";
    if (std::string why = whyNotInMemory(); !why.empty()) return why;
    const uint64_t colorBytes = colorType_ == ANARI_FLOAT32_VEC4 ? 16 : 4;
    return distribution_->whyCannotGather(size_, depth_ ? std::max<uint64_t>(colorBytes, 4) : colorBytes);
}

std::string Frame::whyNotInMemory() {
    const uint32_t channelBits = core::channelFeatures(channels_);
    if (acceptedMemory_ && size_ == acceptedSize_ && colorType_ == acceptedColorType_ && channelBits == acceptedChannels_)
        return {};
    // The buffers of the size rendered so far go when the frame resizes: they count as available.
    AvailableMemory available = availableMemory(state().vulkan());
    if (acceptedMemory_) {
        available.hostBytes += available.unified ? acceptedMemory_->total() : acceptedMemory_->hostBytes;
        available.deviceBytes += acceptedMemory_->deviceBytes;
    }
    const std::optional<FrameMemory> needed = estimateFrameMemory(size_, colorType_, channels_);
    if (std::string why = whyFrameDoesNotFit(size_, needed, available); !why.empty()) return why;
    acceptedMemory_ = needed;
    acceptedSize_ = size_;
    acceptedColorType_ = colorType_;
    acceptedChannels_ = channelBits;
    return {};
}

Frame::Job Frame::makeJob() const {
    Job job;
    job.size = size_;
    job.colorType = colorType_;
    job.depth = depth_;
    job.channels = channels_;
    job.camera = camera_->camera(float(size_.x) / float(size_.y));
    job.settings = renderer_->settings();
    job.completion = completion_;
    job.completionUserData = completionUserData_;
    return job;
}

void Frame::renderFrame() {
    waitForWorker();
    discarded_ = false;
    if (!distribution_) distribution_ = makeFrameDistribution(state().communicator());
    // Collective where data-parallel: every rank learns whether all can render the same frame, so that
    // either all render or none does.
    const std::string why = whyNotRenderable();
    if (!why.empty()) reportError("cannot render: " + why);
    if (const std::string disagreement = distribution_->disagreement(fingerprint(why.empty())); !disagreement.empty()) {
        reportError("cannot render (data-parallel): " + disagreement);
        return;
    }
    if (!why.empty()) return;

    Job job = makeJob();
    // Scene sync runs here, on the application's thread: the objects are only ever read on it.
    const bool sceneChanged = sync_.update(*world_);
    const bool cameraChanged = camera_.get() != renderedCamera_ || camera_->lastCommitted() != renderedCameraStamp_;
    const bool rendererChanged =
        renderer_.get() != renderedRenderer_ || renderer_->lastCommitted() != renderedRendererStamp_;
    job.restartAccumulation =
        distribution_->shareLights(sync_, *world_, sceneChanged || cameraChanged || rendererChanged) || !accumulation_;
    // A world with no light and no emitter anywhere, rendered with "ambientRadiance" unset, would be black:
    // it gets an implicit white ambient light of radiance 1 instead (as the SDK's test scenes and tutorials
    // expect of a device), reported once. An application that sets ambientRadiance, even to 0, gets exactly
    // what it set; any light or emitter turns the implicit light off.
    // (The eyeLight renderer's ambient light is its light at the eye, radiance 1 unless set: it needs none.)
    // anyRank is collective: every rank calls it, whatever its renderer says.
    const bool litAnywhere = distribution_->anyRank(sync_.lit());
    if (!renderer_->ambientGiven() && job.settings.shading == core::RenderSettings::Shading::PathTraced && !litAnywhere) {
        job.settings.ambientRadiance = 1.0f;
        job.settings.ambientColor = glm::vec3(1.0f);
        if (!implicitAmbientReported_)
            state().report(this, ANARI_SEVERITY_INFO, ANARI_STATUS_NO_ERROR,
                           label() + ": the world has no light and no emitter and the renderer no "
                                     "'ambientRadiance': lit by an implicit white ambient light of radiance 1");
        implicitAmbientReported_ = true;
    }
    renderedCamera_ = camera_.get();
    renderedCameraStamp_ = camera_->lastCommitted();
    renderedRenderer_ = renderer_.get();
    renderedRendererStamp_ = renderer_->lastCommitted();

    finished_ = false;
    state().beginWork();
    if (!distribution_->rendersOnWorker()) return run(job);
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
        renderJob(job, start);
    } catch (const std::exception& error) {
        reportError(std::string("rendering failed: ") + error.what());
        distribution_->failed(std::string("rendering failed: ") + error.what());
    } catch (...) {
        reportError("rendering failed: unknown exception");
        distribution_->failed("rendering failed: unknown exception");
    }
    finished_ = true;
    // After the results are in place (anariFrameReady answers 1 and the frame maps inside the callback), and
    // before endWork, so that the device outlives the callback.
    if (job.completion && !discarded_) {
        try {
            job.completion(job.completionUserData, state().handle(), reinterpret_cast<ANARIFrame>(handle()));
        } catch (...) {
            reportError("the frame completion callback threw an exception");
        }
    }
    state().endWork();
}

void Frame::renderJob(const Job& job, const std::chrono::steady_clock::time_point& start) {
    std::lock_guard gpu(gpuMutex());
    vk::Context& context = state().vulkan();
    const uint64_t validationBefore = context.validationMessageCount();
    core::RayExchange* exchange = distribution_->exchange(state().rayExchange());  // the device parameters
    const core::Traversal traversal = state().traversal();
    if (!tracer_ || tracerTraversal_ != traversal || tracerExchange_ != exchange) {
        core::PathTracerOptions options;
        options.exchange = exchange;
        tracer_ = std::make_unique<core::PathTracer>(context, core::TraceOptions{.traversal = traversal}, options);
        tracerTraversal_ = traversal;
        tracerExchange_ = exchange;
    }
    sync_.setTraversal(traversal);

    bool rebuilt = false;
    const core::Scene& scene = distribution_->scene(sync_, context, rebuilt);
    if (rebuilt)
        for (const std::string& message : scene.report().messages) reportWarning("scene: " + message);

    // Resizing clears the accumulation as well.
    if (tracer_->size() != job.size || core::channelFeatures(tracerChannels_) != core::channelFeatures(job.channels)) {
        tracer_->resize(job.size, job.channels);
        tracerChannels_ = job.channels;
    } else if (job.restartAccumulation)
        tracer_->resetAccumulation();

    if (!discarded_) {
        if (exchange) exchange->resetStats();
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
        if (!results.color.empty()) distribution_->gather(job.size, results.color.size() / pixels, results.color.data());
        if (!results.depth.empty()) distribution_->gather(job.size, sizeof(float), results.depth.data());
        results.numSamples = tracer_->accumulatedSamples();
        const double rays = double(stats.raysTraced + stats.shadowRays);
        results.raysTraced = stats.raysTraced + stats.shadowRays;
        results.raysPerSecond = stats.seconds > 0.0 ? float(rays / stats.seconds) : 0.0f;
        results.traversal = core::traversalName(tracer_->traversal());
        results.flaggedRays = stats.flaggedRays;
        results.realCollisions = stats.realCollisions;
        results.nullCollisions = stats.nullCollisions;
        results.ratioCollisions = stats.ratioCollisions;
        results.parkedMarches = stats.parkedMarches;
        for (size_t i = 0; i < core::kStageCount; ++i)
            results.stageMicroseconds[i] = uint64_t(std::llround(stats.stageSeconds[i] * 1e6));
        results.sceneBuilds = sync_.builds();
        results.blasBuilt = scene.report().blasBuilt;
        results.blasReused = scene.report().blasReused;
        results.volumeVoxelsUploaded = scene.report().volumeVoxelsUploaded;
        results.volumeVoxelsReused = scene.report().volumeVoxelsReused;
        results.sceneBytes = scene.report().gpuBytes;
        if (exchange) {
            results.raysSent = exchange->stats().raysSent;
            results.bytesSent = exchange->stats().bytesSent + exchange->stats().regionBytes;
            results.raysReceived = exchange->stats().raysReceived;
            results.exchangeRounds = exchange->stats().hops;
            results.visitMicroseconds = exchange->stats().visitMicroseconds;
        }
        results.duration = std::chrono::duration<float>(std::chrono::steady_clock::now() - start).count();
        std::lock_guard lock(resultsMutex_);
        results_ = std::move(results);
    }
    // Validation runs inside the device, where the application cannot see it: say so through the status
    // callback, as an error, so tests fail on it.
    if (context.validationMessageCount() != validationBefore)
        reportError("Vulkan validation: " + context.lastValidationMessage());
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
    // The completion callback runs on the worker and may map the frame or ask whether it is ready: the
    // render is over by then, and a thread cannot join itself.
    if (worker_.joinable() && worker_.get_id() != std::this_thread::get_id()) worker_.join();
}

bool Frame::ready(bool wait) {
    if (worker_.joinable() && worker_.get_id() == std::this_thread::get_id()) return finished_;
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
    if (name == "ripple.traversal" && type == ANARI_STRING && size >= sizeof(const char*)) {
        std::memcpy(mem, &results_.traversal, sizeof(const char*));  // a static name: valid after the frame
        return true;
    }
    if (name == "numSamples" && type == ANARI_UINT32 && size >= sizeof(uint32_t)) {
        std::memcpy(mem, &results_.numSamples, sizeof(uint32_t));
        return true;
    }
    const std::pair<std::string_view, const uint64_t*> counters[] = {{"ripple.sceneBuilds", &results_.sceneBuilds},
                                                                     {"ripple.blasBuilt", &results_.blasBuilt},
                                                                     {"ripple.blasReused", &results_.blasReused},
                                                                     {"ripple.volumeVoxelsUploaded", &results_.volumeVoxelsUploaded},
                                                                     {"ripple.volumeVoxelsReused", &results_.volumeVoxelsReused},
                                                                     {"ripple.raysSent", &results_.raysSent},
                                                                     {"ripple.bytesSent", &results_.bytesSent},
                                                                     {"ripple.raysReceived", &results_.raysReceived},
                                                                     {"ripple.raysTraced", &results_.raysTraced},
                                                                     {"ripple.exchangeRounds", &results_.exchangeRounds},
                                                                     {"ripple.visitMicroseconds", &results_.visitMicroseconds},
                                                                     {"ripple.sceneBytes", &results_.sceneBytes},
                                                                     {"ripple.flaggedRays", &results_.flaggedRays},
                                                                     {"ripple.realCollisions", &results_.realCollisions},
                                                                     {"ripple.nullCollisions", &results_.nullCollisions},
                                                                     {"ripple.ratioCollisions", &results_.ratioCollisions},
                                                                     {"ripple.parkedMarches", &results_.parkedMarches}};
    for (const auto& [counter, value] : counters) {
        if (name == counter && type == ANARI_UINT64 && size >= sizeof(uint64_t)) {
            std::memcpy(mem, value, sizeof(uint64_t));
            return true;
        }
    }
    constexpr std::string_view kStagePrefix = "ripple.stageMicroseconds.";
    if (name.starts_with(kStagePrefix) && type == ANARI_UINT64 && size >= sizeof(uint64_t))
        for (size_t i = 0; i < core::kStageCount; ++i)
            if (name.substr(kStagePrefix.size()) == core::stageName(core::Stage(i))) {
                std::memcpy(mem, &results_.stageMicroseconds[i], sizeof(uint64_t));
                return true;
            }
    return Object::getProperty(name, type, mem, size, wait);
}

}  // namespace ripple::device
