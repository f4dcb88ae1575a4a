// ripple-render's --time limit over the whole run, start-up included: the clock starts with the process, the
// first frame (which builds the scene on the device and creates the pipelines) ends the start-up, and each
// later frame starts only when the longest of the last few would still end within the limit.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>

namespace ripple::apps {

class TimeBudget {
public:
    using Clock = std::chrono::steady_clock;

    // `limit`: --time in seconds, or none (the budget then only measures); `start`: when the process started.
    TimeBudget(std::optional<double> limit, Clock::time_point start) : limit_(limit), start_(start) {}

    // Seconds since the process started.
    double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

    // A frame ran from `begin` to `end` (elapsed seconds): everything the loop does for it (render, readback,
    // the estimate, a report point). The first one ends the start-up.
    void frameEnded(double begin, double end);

    // Whether a frame started at `now` is predicted to end within the limit (always, without one). The first
    // frame always runs: an image must come out. The second runs whenever time is left, since no frame
    // predicts it (the first, with its pipelines, overstates it); at worst it ends one frame past the limit.
    bool nextFrameFits(double now) const;

    // The start-up ran past the limit: only the first frame (of one sample) is rendered.
    bool startUpExceeded() const { return limit_ && frames_ > 0 && startUpEnd_ >= *limit_; }

    double startUpSeconds() const { return startUpEnd_; }        // to the end of the first frame
    double firstFrameBegin() const { return firstFrameBegin_; }  // library, scene file and scene objects
    double firstFrameSeconds() const { return startUpEnd_ - firstFrameBegin_; }
    double longestFrame() const { return longest_; }             // of the frames after the first; 0: none
    double predictedFrame() const;                               // the longest of the last few; 0: none yet
    uint32_t frames() const { return frames_; }
    std::optional<double> limit() const { return limit_; }

private:
    std::optional<double> limit_;
    Clock::time_point start_;
    uint32_t frames_ = 0;
    double firstFrameBegin_ = 0.0, startUpEnd_ = 0.0, longest_ = 0.0;
    // A single frame's time is noisy on a loaded machine: the longest of the last four predicts the next.
    std::array<double, 4> recent_{};
};

}  // namespace ripple::apps
