// Progressive passes of the viewer through ANARI (see ProgressiveFrames.h).
#include "apps/ripple-view/ProgressiveFrames.h"

#include "apps/scene/AnariParams.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace ripple::apps {
namespace {

glm::uvec2 reducedSize(glm::uvec2 size, uint32_t scale) { return glm::max(size / scale, glm::uvec2(1)); }

// The quick look's light is at the eye (its ambientRadiance, default 1): the scene's ambient fill is not set.
void setQuickLook(ANARIDevice device, ANARIRenderer renderer, const ViewerSettings& settings) {
    anari::set(device, renderer, "pixelSamples", settings.pixelSamples);
    anari::set(device, renderer, "background", settings.background);
    anariCommitParameters(device, renderer);
}

void setRenderer(ANARIDevice device, ANARIRenderer renderer, const ViewerSettings& settings) {
    anari::set(device, renderer, "pixelSamples", settings.pixelSamples);
    anari::set(device, renderer, "maxPathLength", settings.maxPathLength);
    anari::set(device, renderer, "background", settings.background);
    anari::set(device, renderer, "ambientRadiance", settings.ambientRadiance);
    anariCommitParameters(device, renderer);
}

}  // namespace

ProgressiveFrames::ProgressiveFrames(Session& s, const AnariWorld& scene, const CameraView& view, glm::uvec2 size,
                                     const ViewerSettings& settings, uint32_t scale, bool holdsImage)
    : device_(s.device), orthographic_(view.orthographic), size_(size), scale_(std::max(scale, 1u)),
      holdsImage_(holdsImage), view_(view), settings_(settings) {
    const float aspect = float(size.x) / float(size.y);
    camera_ = newAnariCamera(device_, view, aspect);
    renderer_ = anariNewRenderer(device_, "default");
    if (!renderer_) throw std::runtime_error("the device has no 'default' renderer");
    setRenderer(device_, renderer_, settings);
    const std::vector<std::string> renderers = deviceSubtypes(device_, ANARI_RENDERER);
    if (std::find(renderers.begin(), renderers.end(), "eyeLight") != renderers.end()) {
        quickLook_ = anariNewRenderer(device_, "eyeLight");
        if (quickLook_) setQuickLook(device_, quickLook_, settings);
    }
    const bool accumulation = deviceHasExtension(device_, "ANARI_KHR_FRAME_ACCUMULATION");
    for (ANARIFrame* frame : {&full_, &reduced_}) {
        *frame = anariNewFrame(device_);
        if (!*frame) throw std::runtime_error("the device created no frame");
        const ANARIDataType colorType = ANARI_FLOAT32_VEC4;  // linear: screenshots keep the full range
        anari::set(device_, *frame, "size", frame == &full_ ? size : reducedSize(size, scale_));
        anariSetParameter(device_, *frame, "channel.color", ANARI_DATA_TYPE, &colorType);
        if (accumulation) anari::set(device_, *frame, "accumulation", true);
        anari::setObject(device_, *frame, "world", ANARI_WORLD, scene.world);
        anari::setObject(device_, *frame, "renderer", ANARI_RENDERER, movingRenderer(frame == &reduced_));
        anari::setObject(device_, *frame, "camera", ANARI_CAMERA, camera_);
        anariCommitParameters(device_, *frame);
    }
}

ProgressiveFrames::~ProgressiveFrames() {
    if (inFlight_) anariFrameReady(device_, inFlight_, ANARI_WAIT);
    for (ANARIObject o : {ANARIObject(reduced_), ANARIObject(full_), ANARIObject(quickLook_), ANARIObject(renderer_),
                          ANARIObject(camera_)})
        if (o) anariRelease(device_, o);
}

void ProgressiveFrames::setView(const CameraView& view) { pendingView_ = view; }
void ProgressiveFrames::setSettings(const ViewerSettings& settings) {
    if (!(settings == settings_) || pendingSettings_) pendingSettings_ = settings;
}
void ProgressiveFrames::setSize(glm::uvec2 size) {
    if (size != size_ && size.x > 0 && size.y > 0) pendingSize_ = size;
}

void ProgressiveFrames::setReducedScale(uint32_t scale) {
    if (std::max(scale, 1u) != scale_) pendingScale_ = std::max(scale, 1u);
}

void ProgressiveFrames::editScene(std::function<void()> commit) { pendingEdits_.push_back(std::move(commit)); }

void ProgressiveFrames::apply(const PendingChanges& changes) {
    // As pending there, whether or not a value equals this one's current: the same changes restart both.
    if (changes.view) pendingView_ = *changes.view;
    if (changes.settings) pendingSettings_ = *changes.settings;
    if (changes.size) pendingSize_ = *changes.size;
    if (changes.reducedScale) pendingScale_ = *changes.reducedScale;
}

// Called with no pass in flight: the device's objects are only changed between passes.
void ProgressiveFrames::applyPending() {
    if (!pendingEdits_.empty()) {
        for (const std::function<void()>& commit : pendingEdits_) commit();
        pendingEdits_.clear();
        fullStale_ = true;
    }
    if (pendingScale_) {
        scale_ = *pendingScale_;
        pendingScale_.reset();
        if (!pendingSize_) {
            anari::set(device_, reduced_, "size", reducedSize(size_, scale_));
            anariCommitParameters(device_, reduced_);
        }
    }
    if (pendingSize_) {
        size_ = *pendingSize_;
        anari::set(device_, full_, "size", size_);
        anariCommitParameters(device_, full_);
        anari::set(device_, reduced_, "size", reducedSize(size_, scale_));
        anariCommitParameters(device_, reduced_);
        if (!pendingView_) pendingView_ = view_;  // the aspect changed
        pendingSize_.reset();
        fullStale_ = true;
    }
    if (pendingView_) {
        view_ = *pendingView_;
        const float aspect = float(size_.x) / float(size_.y);
        if (view_.orthographic != orthographic_) {  // another kind of camera: a new object
            ANARICamera camera = newAnariCamera(device_, view_, aspect);
            for (ANARIFrame frame : {full_, reduced_}) {
                anari::setObject(device_, frame, "camera", ANARI_CAMERA, camera);
                anariCommitParameters(device_, frame);
            }
            anariRelease(device_, camera_);
            camera_ = camera;
            orthographic_ = view_.orthographic;
        } else {
            setAnariCamera(device_, camera_, view_, aspect);
        }
        pendingView_.reset();
        fullStale_ = true;
    }
    if (pendingSettings_) {
        const bool quickLookChanged = pendingSettings_->quickLookWhileMoving != settings_.quickLookWhileMoving;
        if (pendingSettings_->display != settings_.display) {
            // One extra channel at a time: the one shown (the colour is always there).
            for (ANARIFrame frame : {full_, reduced_}) {
                if (settings_.display != DisplayChannel::Color)
                    anariUnsetParameter(device_, frame, displayChannelInfo(settings_.display).parameter);
                if (pendingSettings_->display != DisplayChannel::Color) {
                    const DisplayChannelInfo& shown = displayChannelInfo(pendingSettings_->display);
                    anariSetParameter(device_, frame, shown.parameter, ANARI_DATA_TYPE, &shown.type);
                }
                anariCommitParameters(device_, frame);
            }
        }
        settings_ = *pendingSettings_;
        setRenderer(device_, renderer_, settings_);
        if (quickLook_) setQuickLook(device_, quickLook_, settings_);
        if (quickLookChanged) {
            anari::setObject(device_, reduced_, "renderer", ANARI_RENDERER, movingRenderer(true));
            anariCommitParameters(device_, reduced_);
        }
        pendingSettings_.reset();
        fullStale_ = true;
    }
}

ANARIRenderer ProgressiveFrames::movingRenderer(bool reducedFrame) const {
    return reducedFrame && quickLook_ && settings_.quickLookWhileMoving ? quickLook_ : renderer_;
}

bool ProgressiveFrames::passDue(bool moving, uint32_t maxSamples) const {
    if (inFlight_) return false;
    // A new view, size or settings restart the full frame (applyPending), whatever it holds.
    const bool restarts = fullStale_ || pendingView_ || pendingSize_ || pendingSettings_ || !pendingEdits_.empty();
    return moving || restarts || maxSamples == 0 || fullSamples_ < maxSamples;
}

bool ProgressiveFrames::startPass(bool moving, uint32_t maxSamples) {
    if (!passDue(moving, maxSamples)) return false;
    applyPending();
    inFlight_ = moving ? reduced_ : full_;
    if (!moving && fullStale_) {
        fullSamples_ = 0;
        fullStale_ = false;
        estimatorStale_ = true;
    }
    passBegin_ = std::chrono::steady_clock::now();
    anariRenderFrame(device_, inFlight_);
    return true;
}

bool ProgressiveFrames::poll(bool wait) {
    if (!inFlight_ || !anariFrameReady(device_, inFlight_, wait ? ANARI_WAIT : ANARI_NO_WAIT)) return false;
    const ANARIFrame frame = inFlight_;
    inFlight_ = nullptr;
    readPass(frame, frame == reduced_);
    return true;
}

void ProgressiveFrames::readPass(ANARIFrame frame, bool reduced) {
    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - passBegin_).count();
    PassResult& r = latest_;
    r.reduced = reduced;
    float seconds = 0.0f;
    r.milliseconds = anariGetProperty(device_, frame, "duration", ANARI_FLOAT32, &seconds, sizeof seconds, ANARI_WAIT)
                         ? double(seconds) * 1e3 : wall;
    float rays = 0.0f;
    if (hasRays_)
        hasRays_ = anariGetProperty(device_, frame, "ripple.raysPerSecond", ANARI_FLOAT32, &rays, sizeof rays, ANARI_WAIT);
    r.raysPerSecond = hasRays_ ? std::optional<float>(rays) : std::nullopt;
    // The samples this pass holds: the device's count, else one more pass of pixelSamples on the full
    // frame (a reduced pass restarts: its view changed).
    uint32_t samples = 0;
    if (countsSamples_)
        countsSamples_ = anariGetProperty(device_, frame, "numSamples", ANARI_UINT32, &samples, sizeof samples, ANARI_WAIT);
    if (!countsSamples_)
        samples = (reduced ? 0 : fullSamples_) + uint32_t(settings_.pixelSamples);
    r.samples = samples;
    if (!reduced) fullSamples_ = samples;
    if (!holdsImage_) return;

    uint32_t width = 0, height = 0;
    ANARIDataType type = ANARI_UNKNOWN;
    const void* pixels = anariMapFrame(device_, frame, "channel.color", &width, &height, &type);
    if (!pixels || type != ANARI_FLOAT32_VEC4 || width == 0 || height == 0) {
        if (pixels) anariUnmapFrame(device_, frame, "channel.color");
        throw std::runtime_error("the device returned no FLOAT32_VEC4 color channel");
    }
    r.size = {width, height};
    const size_t floats = size_t(width) * height * 4;
    r.rgba.assign(static_cast<const float*>(pixels), static_cast<const float*>(pixels) + floats);
    anariUnmapFrame(device_, frame, "channel.color");
    r.display.clear();
    if (settings_.display != DisplayChannel::Color) {
        const DisplayChannelInfo& shown = displayChannelInfo(settings_.display);
        uint32_t w = 0, h = 0;
        ANARIDataType shownType = ANARI_UNKNOWN;
        const void* values = anariMapFrame(device_, frame, shown.parameter, &w, &h, &shownType);
        // A device without the channel shows the colour (it has reported the unknown parameter).
        if (values && w == width && h == height && shownType == shown.type)
            r.display = channelPicture(settings_.display, values, size_t(w) * h);
        if (values) anariUnmapFrame(device_, frame, shown.parameter);
    }
    if (!reduced) {  // the full frame's restart (startPass) starts the estimate over
        if (estimatorStale_ || !estimator_ || samples <= estimator_->samples() ||
            glm::uvec2(width, height) != estimator_->size()) {
            estimator_.emplace(width, height);
            estimatorStale_ = false;
            r.estimate = {};
        }
        estimator_->addAccumulatedFrame(r.rgba.data(), samples);
        // The estimate costs a pass over the image: at most every half second (and always while it has none).
        const auto now = std::chrono::steady_clock::now();
        if (std::isnan(r.estimate.relMse) || now - lastEstimate_ > std::chrono::milliseconds(500)) {
            r.estimate = estimator_->estimate();
            lastEstimate_ = now;
        }
    } else {
        r.estimate = {};  // the view changed: the full frame starts over
    }
}

}  // namespace ripple::apps
