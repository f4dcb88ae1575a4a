// Frame parameters, the asynchronous render on a worker thread, and channel mapping (see Frame.h).
#include "anari/device/frame/Frame.h"

#include "anari/device/object/DeviceState.h"
#include "core/vk/Context.h"

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

Frame::Frame(DeviceState& state) : Object(state, ANARI_FRAME, "") {}

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
    const ANARIDataType depthType = pullChannel("channel.depth");
    depth_ = depthType == ANARI_FLOAT32;
    if (depthType != ANARI_UNKNOWN && !depth_)
        reportError(std::string("parameter 'channel.depth' is ") + ripple_anari::typeName(depthType) +
                    "; supported is FLOAT32. Channel disabled");
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
    if (const std::string why = whyNotRenderable(); !why.empty()) {
        reportError("cannot render: " + why);
        return;
    }

    Job job;
    job.size = size_;
    job.colorType = colorType_;
    job.depth = depth_;
    job.camera = camera_->camera(float(size_.x) / float(size_.y));
    job.settings = renderer_->settings();
    // Scene sync runs here, on the application's thread: the objects are only ever read on it.
    const bool sceneChanged = sync_.update(*world_);
    const bool cameraChanged = camera_.get() != renderedCamera_ || camera_->lastCommitted() != renderedCameraStamp_;
    const bool rendererChanged =
        renderer_.get() != renderedRenderer_ || renderer_->lastCommitted() != renderedRendererStamp_;
    job.restartAccumulation = sceneChanged || cameraChanged || rendererChanged;
    renderedCamera_ = camera_.get();
    renderedCameraStamp_ = camera_->lastCommitted();
    renderedRenderer_ = renderer_.get();
    renderedRendererStamp_ = renderer_->lastCommitted();

    finished_ = false;
    state().beginWork();
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
        if (!tracer_) tracer_ = std::make_unique<core::PathTracer>(context);

        bool rebuilt = false;
        const core::Scene& scene = sync_.scene(context, rebuilt);
        if (rebuilt)
            for (const std::string& message : scene.report().messages) reportWarning("scene: " + message);

        // Resizing clears the accumulation as well.
        if (tracer_->size() != job.size || tracerHasDepth_ != job.depth) {
            tracer_->resize(job.size, job.depth);
            tracerHasDepth_ = job.depth;
        } else if (job.restartAccumulation)
            tracer_->resetAccumulation();

        if (!discarded_) {
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
            results.numSamples = tracer_->accumulatedSamples();
            const double rays = double(stats.raysTraced + stats.shadowRays);
            results.raysPerSecond = stats.seconds > 0.0 ? float(rays / stats.seconds) : 0.0f;
            results.sceneBuilds = sync_.builds();
            results.blasBuilt = scene.report().blasBuilt;
            results.blasReused = scene.report().blasReused;
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
    } catch (...) {
        reportError("rendering failed: unknown exception");
    }
    finished_ = true;
    state().endWork();
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
    } else {
        reportError("channel '" + std::string(channel) +
                    "' cannot be mapped: it was not enabled (channel.color / channel.depth), or nothing was rendered");
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
                                                                     {"ripple.blasReused", &results_.blasReused}};
    for (const auto& [counter, value] : counters) {
        if (name == counter && type == ANARI_UINT64 && size >= sizeof(uint64_t)) {
            std::memcpy(mem, value, sizeof(uint64_t));
            return true;
        }
    }
    return Object::getProperty(name, type, mem, size, wait);
}

}  // namespace ripple::device
