// The half-buffer error estimate. Sums are kept in double: recovering a batch as the difference of two large
// accumulated sums would lose it in float.
#include "metrics/ErrorEstimate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ripple::apps {

HalfBufferEstimator::HalfBufferEstimator(uint32_t width, uint32_t height)
    : width_(width), height_(height), previousSum_(size_t(width) * height * 4, 0.0) {
    halfSum_[0].assign(previousSum_.size(), 0.0);
    halfSum_[1].assign(previousSum_.size(), 0.0);
}

void HalfBufferEstimator::addAccumulatedFrame(const float* mean, uint32_t totalSamples) {
    if (totalSamples <= previousSamples_)
        throw std::runtime_error("the device's sample count went from " + std::to_string(previousSamples_) + " to " +
                                 std::to_string(totalSamples) + ": it restarted its accumulation");
    std::vector<double>& half = nextHalf(totalSamples - previousSamples_);
    for (size_t i = 0; i < half.size(); ++i) {
        const double sum = double(mean[i]) * double(totalSamples);
        half[i] += sum - previousSum_[i];
        previousSum_[i] = sum;
    }
    previousSamples_ = totalSamples;
}

void HalfBufferEstimator::addBatchFrame(const float* mean, uint32_t batchSamples) {
    if (batchSamples == 0) throw std::runtime_error("a frame of 0 samples");
    std::vector<double>& half = nextHalf(batchSamples);
    for (size_t i = 0; i < half.size(); ++i) half[i] += double(mean[i]) * double(batchSamples);
}

std::vector<double>& HalfBufferEstimator::nextHalf(uint32_t batchSamples) {
    // Alternate batches, so that each half is an independent estimate of the same image.
    const int half = int(batches_ % 2);
    halfSamples_[half] += batchSamples;
    ++batches_;
    return halfSum_[half];
}

HalfBufferEstimator::PixelErrors HalfBufferEstimator::pixelErrors(double epsilon) const {
    const double nA = halfSamples_[0], nB = halfSamples_[1];
    if (nA == 0 || nB == 0) return {};
    const double varianceFactor = nA * nB / ((nA + nB) * (nA + nB));  // Var(F) = E[(A - B)^2] * this
    const double n = nA + nB;
    const int w = int(width_), h = int(height_);
    PixelErrors errors;
    errors.map.assign(size_t(width_) * height_, 0.0);
    double neighbours[8];
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t p = size_t(y) * width_ + size_t(x);
            double pixel = 0.0;
            for (size_t c = 0; c < 3; ++c) {
                int count = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = x + dx, ny = y + dy;
                        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                        const size_t i = (size_t(ny) * width_ + size_t(nx)) * 4 + c;
                        const double neighbour = (halfSum_[0][i] + halfSum_[1][i]) / n;
                        if (std::isfinite(neighbour)) neighbours[count++] = neighbour;  // NaN would break the order
                    }
                // The median (of an even count, the mean of the middle two): a neighbour's firefly never enters.
                double median = 0.0;
                if (count > 0) {
                    double* upper = neighbours + count / 2;
                    std::nth_element(neighbours, upper, neighbours + count);
                    median = *upper;
                    if (count % 2 == 0) median = 0.5 * (median + *std::max_element(neighbours, upper));
                }
                const size_t i = p * 4 + c;
                const double a = halfSum_[0][i] / nA, b = halfSum_[1][i] / nB;
                const double full = (halfSum_[0][i] + halfSum_[1][i]) / n;  // a 1x1 image has no neighbours
                if (!std::isfinite(a) || !std::isfinite(b)) {  // a NaN or Inf pixel makes the estimate NaN, not wrong
                    pixel = std::numeric_limits<double>::quiet_NaN();
                    errors.optimisticTotal = pixel;
                    continue;
                }
                const double mean = std::clamp(count > 0 ? median : full, std::min(a, b), std::max(a, b));
                const double m = std::max(mean, 0.0);
                const double variance = (a - b) * (a - b) * varianceFactor;
                pixel += variance / (m * m + epsilon);
                errors.optimisticTotal += variance / (full * full + epsilon);
            }
            // Bottom row first in the sums, row 0 at the top in the map.
            errors.map[size_t(h - 1 - y) * width_ + size_t(x)] = pixel / 3.0;
        }
    return errors;
}

std::vector<double> HalfBufferEstimator::errorMap(double epsilon) const { return pixelErrors(epsilon).map; }

ErrorEstimate HalfBufferEstimator::estimate(double epsilon) const {
    const PixelErrors errors = pixelErrors(epsilon);
    if (errors.map.empty()) return {};
    double total = 0.0;
    for (double e : errors.map) total += e;
    const double relMse = total / double(errors.map.size());
    const double optimistic = errors.optimisticTotal / double(errors.map.size() * 3);
    return {relMse, std::min(optimistic, relMse) / kBandBelow, std::max(optimistic, relMse) * kBandAbove};
}

std::vector<float> HalfBufferEstimator::meanRgbaBottomUp() const {
    std::vector<float> rgba(previousSum_.size(), 0.0f);
    const double n = samples();
    if (n == 0) return rgba;
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = float((halfSum_[0][i] + halfSum_[1][i]) / n);
    return rgba;
}

LinearImage HalfBufferEstimator::meanImage() const {
    const std::vector<float> rgba = meanRgbaBottomUp();
    LinearImage image;
    image.width = width_;
    image.height = height_;
    image.rgb.resize(size_t(width_) * height_ * 3);
    for (uint32_t y = 0; y < height_; ++y)
        for (uint32_t x = 0; x < width_; ++x)
            for (size_t c = 0; c < 3; ++c)
                image.rgb[(size_t(y) * width_ + x) * 3 + c] = rgba[(size_t(height_ - 1 - y) * width_ + x) * 4 + c];
    return image;
}

}  // namespace ripple::apps
