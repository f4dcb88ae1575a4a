// How far a progressive render is from converged, with no reference image: each frame's samples are dealt
// alternately into two half-buffers, whose difference estimates the variance of the full image
// (docs/error-estimate.md). ripple-render reports it against run time; ripple-view shows it.
#pragma once

#include "metrics/ImageMetrics.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <vector>

namespace ripple::apps {

// The epsilon of relMSE's denominator, shared by the estimate and the true relMSE so that they compare.
inline constexpr double kRelMseEpsilon = 1e-2;

// Two half-buffers of batches of samples. With n_A and n_B samples in the halves, A and B their means and
// F the full mean, Var(A) = s^2/n_A, Var(B) = s^2/n_B and Var(F) = s^2/(n_A + n_B), so
//   E[(A - B)^2] = s^2 (n_A + n_B) / (n_A n_B)  and  Var(F) = E[(A - B)^2] n_A n_B / (n_A + n_B)^2,
// which is E[(A - B)^2] / 4 for equal halves. Summed over pixels this numerator tracks the image's own
// squared error (F - mu)^2, fireflies included: both hold (A - mu)^2 + (B - mu)^2, and the cross terms,
// which differ in sign, cancel over many pixels. Everything then hangs on the denominator, the square of
// the true mean mu (relMSE divides each pixel's squared error by mu^2 + epsilon):
//   estimate = mean over pixels and RGB of ((A - B)^2 n_A n_B / (n_A + n_B)^2) / (m^2 + epsilon),
//   m = the median of F over the pixel's (up to 8) neighbours, clamped to [min(A, B), max(A, B)].
// A firefly in one half inflates F^2 and A B exactly where it inflates the numerator, which made the
// earlier denominators optimistic by 2-20x on the shared scenes; the neighbours' median does not see the
// pixel's own samples, and the clamp keeps it to what the pixel's own halves allow where the image has
// detail at the scale of a pixel. docs/error-estimate.md has the measured calibration.
//
// No estimate from the image's own samples can tell a firefly (a rare sample far above a small mean) from a
// highlight smaller than a pixel (rare samples that make up a large mean): the first wants the neighbours'
// mean in the denominator, the second F. So the estimate comes with a band: from the lower of it and the
// optimistic value with F^2 as the denominator, divided by kBandBelow, to the higher times kBandAbove. Where
// the two agree (no heavy tails) the band is narrow; a wide band says the image holds pixels whose mean it
// cannot pin down. The margins cover the estimate's measured spread: 0.67 to 1.30 times the true relMSE on
// the shared and demo scenes without heavy tails, down to 0.54 on one with a firefly (docs/error-estimate.md).
inline constexpr double kBandBelow = 1.3, kBandAbove = 2.0;

struct ErrorEstimate {
    static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
    double relMse = kNone;            // the estimate; NaN: none yet
    double low = kNone, high = kNone; // the band the true relMSE is expected in
};

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
    glm::uvec2 size() const { return {width_, height_}; }
    uint32_t batches() const { return batches_; }
    // The estimate above; NaN until each half holds a batch.
    double estimatedRelMse(double epsilon = kRelMseEpsilon) const { return estimate(epsilon).relMse; }
    // The estimate and its band; all NaN until each half holds a batch.
    ErrorEstimate estimate(double epsilon = kRelMseEpsilon) const;
    // Each pixel's share of it (its estimated relMSE, the mean over RGB), row 0 at the top; empty until each
    // half holds a batch.
    std::vector<double> errorMap(double epsilon = kRelMseEpsilon) const;
    // The full mean as RGBA floats, bottom row first (as a device maps it); alpha is averaged like colour.
    std::vector<float> meanRgbaBottomUp() const;
    // The full mean's RGB, row 0 at the top (for the image metrics).
    LinearImage meanImage() const;

private:
    struct PixelErrors {
        std::vector<double> map;  // each pixel's estimate, row 0 at the top
        double optimisticTotal = 0.0;  // the sum over pixels and RGB with F^2 as the denominator
    };
    PixelErrors pixelErrors(double epsilon) const;
    // The half the next batch goes to, its counts advanced.
    std::vector<double>& nextHalf(uint32_t batchSamples);

    uint32_t width_, height_;
    std::vector<double> previousSum_;  // S_{k-1}: the accumulated sum after the previous frame, RGBA
    uint32_t previousSamples_ = 0;
    std::vector<double> halfSum_[2];  // RGBA sums of the batches dealt to each half
    uint32_t halfSamples_[2] = {0, 0};
    uint32_t batches_ = 0;
};

}  // namespace ripple::apps
