// The progress line ripple-render draws on stderr while frames accumulate: samples done of total, elapsed
// time, estimated time left and, where the device reports it, the ray rate of the latest frame.
#pragma once

#include <chrono>
#include <cstdint>

namespace ripple::apps {

class Progress {
public:
    // `enabled` false draws nothing. On a terminal the line redraws in place; elsewhere (a log) each update
    // is its own line.
    Progress(uint32_t totalSamples, bool enabled);

    // `raysPerSecond` is 0 when the device does not report it.
    void update(uint32_t samplesDone, float raysPerSecond);
    void finish();
    double elapsedSeconds() const;

private:
    uint32_t total_;
    bool enabled_;
    bool terminal_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace ripple::apps
