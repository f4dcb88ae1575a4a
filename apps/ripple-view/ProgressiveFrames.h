// The viewer's ANARI side: one world rendered progressively into two frames sharing a camera and a renderer,
// the full-size one while the view is still and a reduced one while it moves, one pass in flight at a time
// (anariRenderFrame, then anariFrameReady polled with ANARI_NO_WAIT), so the window never waits for the device.
// The reduced frame renders with the device's quick-look renderer ("eyeLight") where it has one and the
// settings ask for it.
// Changes wait until no pass is in flight and restart the accumulation (the device sees a new commit).
#pragma once

#include "apps/ripple-view/ChannelView.h"
#include "apps/scene/AnariScene.h"
#include "apps/scene/AnariSession.h"
#include "metrics/ErrorEstimate.h"

#include <anari/anari.h>

#include <glm/glm.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace ripple::apps {

// The renderer's parameters the viewer edits.
struct ViewerSettings {
    int32_t pixelSamples = 1;           // samples per pixel in one pass
    int32_t maxPathLength = 5;
    glm::vec4 background{0.0f, 0.0f, 0.0f, 1.0f};
    float ambientRadiance = 0.0f;
    // While the view moves, render with the device's "eyeLight" renderer (a quick look: first surfaces lit
    // from the eye), where the device has one; the path tracer takes over when the view is still.
    bool quickLookWhileMoving = true;
    DisplayChannel display = DisplayChannel::Color;  // what the window shows
    bool operator==(const ViewerSettings&) const = default;
};

// The image and numbers of the last pass that ended.
struct PassResult {
    glm::uvec2 size{0, 0};
    std::vector<float> rgba;            // linear, bottom row first, as the color channel maps
    std::vector<float> display;         // the picture of ViewerSettings::display, as rgba; empty: the colour
    bool reduced = false;               // rendered at reduced size while the view moved
    uint32_t samples = 0;               // per pixel accumulated in it
    double milliseconds = 0.0;          // the pass on the device ("duration"), else wall time to ready
    std::optional<float> raysPerSecond; // the device's "ripple.raysPerSecond", when it has it
    // The full-size frame's estimated relMSE and its band, as ripple-render reports it (NaN until its
    // accumulation holds two passes, and on moving passes: the view changed), recomputed at most every
    // half second.
    ErrorEstimate estimate;
};

// The changes the next pass takes up (setView, setSettings, setSize, setReducedScale since the last pass):
// under mpirun rank 0 sends them to the other ranks, whose frames must render exactly what its frames render.
struct PendingChanges {
    std::optional<CameraView> view;
    std::optional<ViewerSettings> settings;
    std::optional<glm::uvec2> size;
    std::optional<uint32_t> reducedScale;
};

class ProgressiveFrames {
public:
    // Makes the camera, renderer and both frames on the session's device (released here, after waiting for
    // a pass in flight; the session must outlive this); `scale` divides each side of the reduced frame.
    // holdsImage false: a data-parallel rank other than 0, which renders its part of every pass but has no
    // image to read (latest() keeps only the pass's sample count).
    ProgressiveFrames(Session& s, const AnariWorld& scene, const CameraView& view, glm::uvec2 size,
                      const ViewerSettings& settings, uint32_t scale = 2, bool holdsImage = true);
    ~ProgressiveFrames();
    ProgressiveFrames(const ProgressiveFrames&) = delete;
    ProgressiveFrames& operator=(const ProgressiveFrames&) = delete;

    // Take effect with the next pass, restarting the accumulation.
    void setView(const CameraView& view);
    void setSettings(const ViewerSettings& settings);
    void setSize(glm::uvec2 size);
    // Each side of the reduced frame is the full size divided by `scale` (1: moving passes are full size,
    // but still restart).
    void setReducedScale(uint32_t scale);
    // A change to the scene's objects (SceneEdits::commit calls): `commit` runs before the next pass, when
    // none is in flight, and the accumulation restarts.
    void editScene(std::function<void()> commit);

    PendingChanges pending() const { return {pendingView_, pendingSettings_, pendingSize_, pendingScale_}; }
    // Takes up another instance's pending() as its own pending changes, so that the next pass here
    // restarts where that instance's restarts.
    void apply(const PendingChanges& changes);

    // Whether startPass(moving, maxSamples) would start a pass now.
    bool passDue(bool moving, uint32_t maxSamples = 0) const;
    // Starts a pass when none is in flight: on the reduced frame when `moving`, else on the full-size one
    // unless it already holds `maxSamples` (0: no limit). Returns whether one started.
    bool startPass(bool moving, uint32_t maxSamples = 0);
    // Whether a pass ended since the last call (wait: blocks until it does); its image is then in latest().
    bool poll(bool wait = false);
    bool busy() const { return inFlight_ != nullptr; }
    // Whether the device has the quick-look renderer that quickLookWhileMoving selects.
    bool hasQuickLook() const { return quickLook_ != nullptr; }

    const PassResult& latest() const { return latest_; }
    // The full frame's estimate from all its passes so far (latest().estimate may be half a second old).
    ErrorEstimate estimateNow() const { return estimator_ ? estimator_->estimate() : ErrorEstimate{}; }
    // Samples per pixel of the full-size frame since its last restart (0 before its first pass).
    uint32_t fullSamples() const { return fullSamples_; }
    glm::uvec2 size() const { return size_; }

private:
    void applyPending();
    // The renderer of the reduced frame (reducedFrame) or of the full one.
    ANARIRenderer movingRenderer(bool reducedFrame) const;
    void readPass(ANARIFrame frame, bool reduced);

    ANARIDevice device_;
    ANARICamera camera_ = nullptr;
    ANARIRenderer renderer_ = nullptr;
    ANARIRenderer quickLook_ = nullptr;  // "eyeLight", when the device has it
    ANARIFrame full_ = nullptr, reduced_ = nullptr;
    bool orthographic_ = false;
    glm::uvec2 size_;
    uint32_t scale_;
    bool holdsImage_;
    std::optional<CameraView> pendingView_;
    std::optional<ViewerSettings> pendingSettings_;
    std::optional<glm::uvec2> pendingSize_;
    std::optional<uint32_t> pendingScale_;
    std::vector<std::function<void()>> pendingEdits_;
    CameraView view_;
    ViewerSettings settings_;
    bool fullStale_ = true;             // the full frame restarts with its next pass
    uint32_t fullSamples_ = 0;
    std::optional<HalfBufferEstimator> estimator_;  // the full frame's passes since its restart
    bool estimatorStale_ = true;        // the full frame restarted: the estimator starts over
    std::chrono::steady_clock::time_point lastEstimate_;
    bool countsSamples_ = true;         // the device answers "numSamples"
    bool hasRays_ = true;               // the device answers "ripple.raysPerSecond"
    ANARIFrame inFlight_ = nullptr;
    std::chrono::steady_clock::time_point passBegin_;
    PassResult latest_;
};

}  // namespace ripple::apps
