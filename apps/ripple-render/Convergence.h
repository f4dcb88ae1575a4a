// The series ripple-render reports (time, spp, the error estimate of metrics/ErrorEstimate.h and, given
// a reference, the true error), its CSV, and a render clock that leaves the reporting out.
#pragma once

#include "metrics/ErrorEstimate.h"
#include "metrics/ImageMetrics.h"

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ripple::apps {

// True error against a converged reference (ImageMetrics).
struct ReferenceMetrics {
    double relMse = 0.0, psnr = 0.0, ssim = 0.0, flipLdr = 0.0, flipHdr = 0.0;
};
// `flip` is `reference` prepared for both FLIP measures (built once for a whole series).
ReferenceMetrics compareToReference(const LinearImage& image, const LinearImage& reference, const FlipReference& flip);

struct ConvergencePoint {
    double seconds = 0.0;  // render time so far, time spent on reference metrics excluded
    uint32_t spp = 0;
    ErrorEstimate estimate;
    std::optional<ReferenceMetrics> reference;
};

// The spp of the report point after `spp`: about 1.2 times further (at least one more sample), so that the
// points lie evenly on a log axis, and every power of two (the spp that renders and tests compare at).
uint32_t nextReportSpp(uint32_t spp);

// One line for the terminal: time, spp, the estimate with its band and the reference metrics when there are any.
std::string formatConvergencePoint(const ConvergencePoint& point);

// CSV with the header time_s,spp,estimated_relmse,band_low,band_high and, when the points carry reference metrics,
// relmse,psnr_db,ssim,flip_ldr,flip_hdr. Throws std::runtime_error naming the file when it cannot be written.
void writeConvergenceCsv(const std::filesystem::path& file, const std::vector<ConvergencePoint>& points);

// Wall time that can leave out stretches (reference metrics, reporting) so that they do not count as render
// time.
class RenderClock {
public:
    RenderClock() : start_(std::chrono::steady_clock::now()) {}
    double seconds() const;
    // Time between pause() and resume() is not counted.
    void pause();
    void resume();

private:
    std::chrono::steady_clock::time_point start_, pausedAt_;
    double excluded_ = 0.0;
    bool paused_ = false;
};

}  // namespace ripple::apps
