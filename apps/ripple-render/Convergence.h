// How far a progressive render is from converged, with no reference image: each frame's samples are dealt
// alternately into two half-buffers, whose difference estimates the variance of the full image; plus the
// series ripple-render reports (time, spp, estimate and, given a reference, the true error) and its CSV.
#pragma once

#include "apps/common/ImageMetrics.h"

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ripple::apps {

// The epsilon of relMSE's denominator, shared by the estimate and the true relMSE so that they compare.
inline constexpr double kRelMseEpsilon = 1e-2;

// Two half-buffers of batches of samples. With n_A and n_B samples in the halves, A and B their means and
// F the full mean, Var(A) = s^2/n_A, Var(B) = s^2/n_B and Var(F) = s^2/(n_A + n_B), so
//   E[(A - B)^2] = s^2 (n_A + n_B) / (n_A n_B)  and  Var(F) = E[(A - B)^2] n_A n_B / (n_A + n_B)^2,
// which is E[(A - B)^2] / 4 for equal halves. The estimate of the full image's relMSE is
//   mean over pixels and RGB channels of  ((A - B)^2 n_A n_B / (n_A + n_B)^2) / (max(A B, 0) + epsilon),
// the variance part of relMSE (an unbiased renderer has no other). The halves are independent, so
// E[A B] = mu^2, the true mean's square; F^2 instead (E[F^2] = mu^2 + Var(F)) sits high exactly where a
// bright sample makes the numerator large, and measured 0.52-0.75 of the true relMSE over the first 8 spp
// of the Cornell test and 0.05-0.3 on the default demo's fireflies (A B: 1.38, then 0.97-1.08; 0.1-0.4).
class HalfBufferEstimator {
public:
    HalfBufferEstimator(uint32_t width, uint32_t height);

    // A frame's color channel as mapped (width * height RGBA floats, bottom row first) holding the AVERAGE
    // of all `totalSamples` samples so far (an accumulating device): the batch just added is recovered as
    // S_k - S_{k-1} with S_k = totalSamples * mean. Throws when totalSamples does not grow (the device
    // restarted its accumulation).
    void addAccumulatedFrame(const float* mean, uint32_t totalSamples);
    // A frame holding only its own `batchSamples` samples' average (a device that does not accumulate).
    void addBatchFrame(const float* mean, uint32_t batchSamples);

    uint32_t samples() const { return halfSamples_[0] + halfSamples_[1]; }
    uint32_t batches() const { return batches_; }
    // The estimate above; NaN until each half holds a batch.
    double estimatedRelMse(double epsilon = kRelMseEpsilon) const;
    // The full mean as RGBA floats, bottom row first (as a device maps it); alpha is averaged like colour.
    std::vector<float> meanRgbaBottomUp() const;
    // The full mean's RGB, row 0 at the top (for the image metrics).
    LinearImage meanImage() const;

private:
    void addBatchSums(const std::vector<double>& batchSum, uint32_t batchSamples);

    uint32_t width_, height_;
    std::vector<double> previousSum_;  // S_{k-1}: the accumulated sum after the previous frame, RGBA
    uint32_t previousSamples_ = 0;
    std::vector<double> halfSum_[2];  // RGBA sums of the batches dealt to each half
    uint32_t halfSamples_[2] = {0, 0};
    uint32_t batches_ = 0;
};

// True error against a converged reference (ImageMetrics).
struct ReferenceMetrics {
    double relMse = 0.0, psnr = 0.0, ssim = 0.0, flipLdr = 0.0, flipHdr = 0.0;
};
ReferenceMetrics compareToReference(const LinearImage& image, const LinearImage& reference);

struct ConvergencePoint {
    double seconds = 0.0;  // render time so far, time spent on reference metrics excluded
    uint32_t spp = 0;
    double estimatedRelMse = 0.0;
    std::optional<ReferenceMetrics> reference;
};

// The spp of the report point after `spp`: about 1.2 times further (at least one more sample), so that the
// points lie evenly on a log axis.
uint32_t nextReportSpp(uint32_t spp);

// One line for the terminal: time, spp, the estimate and the reference metrics when there are any.
std::string formatConvergencePoint(const ConvergencePoint& point);

// CSV with the header time_s,spp,estimated_relmse and, when the points carry reference metrics,
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
