// Half-buffer error estimate, the report series and its CSV. Sums are kept in double: recovering a batch as
// the difference of two large accumulated sums would lose it in float.
#include "apps/ripple-render/Convergence.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>

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
    std::vector<double> batchSum(previousSum_.size());
    for (size_t i = 0; i < batchSum.size(); ++i) {
        const double sum = double(mean[i]) * double(totalSamples);
        batchSum[i] = sum - previousSum_[i];
        previousSum_[i] = sum;
    }
    addBatchSums(batchSum, totalSamples - previousSamples_);
    previousSamples_ = totalSamples;
}

void HalfBufferEstimator::addBatchFrame(const float* mean, uint32_t batchSamples) {
    if (batchSamples == 0) throw std::runtime_error("a frame of 0 samples");
    std::vector<double> batchSum(previousSum_.size());
    for (size_t i = 0; i < batchSum.size(); ++i) batchSum[i] = double(mean[i]) * double(batchSamples);
    addBatchSums(batchSum, batchSamples);
}

void HalfBufferEstimator::addBatchSums(const std::vector<double>& batchSum, uint32_t batchSamples) {
    // Alternate batches, so that each half is an independent estimate of the same image.
    const int half = int(batches_ % 2);
    for (size_t i = 0; i < batchSum.size(); ++i) halfSum_[half][i] += batchSum[i];
    halfSamples_[half] += batchSamples;
    ++batches_;
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
                        neighbours[count++] = (halfSum_[0][i] + halfSum_[1][i]) / n;
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
    if (errors.map.empty()) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        return {nan, nan, nan};
    }
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

ReferenceMetrics compareToReference(const LinearImage& image, const LinearImage& reference) {
    ReferenceMetrics m;
    m.relMse = relMse(image, reference, kRelMseEpsilon);
    m.psnr = psnr(image, reference);
    m.ssim = ssim(image, reference);
    m.flipLdr = flipLdr(image, reference);
    m.flipHdr = flipHdr(image, reference);
    return m;
}

uint32_t nextReportSpp(uint32_t spp) {
    const uint32_t next = std::max(spp + 1, uint32_t(std::lround(double(spp) * 1.2)));
    uint32_t powerOfTwo = 1;
    while (powerOfTwo <= spp) powerOfTwo *= 2;
    return std::min(next, powerOfTwo);
}

std::string formatConvergencePoint(const ConvergencePoint& point) {
    char line[256];
    int n = std::snprintf(line, sizeof line, "%8.2f s %7u spp  estimated relMSE %.3e (%.1e .. %.1e)", point.seconds,
                          point.spp, point.estimate.relMse, point.estimate.low, point.estimate.high);
    if (point.reference && n > 0 && size_t(n) < sizeof line) {
        const ReferenceMetrics& r = *point.reference;
        std::snprintf(line + n, sizeof line - size_t(n), "  relMSE %.3e  PSNR %.2f dB  SSIM %.4f  FLIP %.4f (HDR %.4f)",
                      r.relMse, r.psnr, r.ssim, r.flipLdr, r.flipHdr);
    }
    return line;
}

void writeConvergenceCsv(const std::filesystem::path& file, const std::vector<ConvergencePoint>& points) {
    std::ofstream out(file);
    if (!out) throw std::runtime_error(file.string() + ": cannot write the report");
    const bool withReference = !points.empty() && points.front().reference.has_value();
    out << "time_s,spp,estimated_relmse,band_low,band_high" << (withReference ? ",relmse,psnr_db,ssim,flip_ldr,flip_hdr" : "") << "\n";
    char line[256];
    for (const ConvergencePoint& p : points) {
        std::snprintf(line, sizeof line, "%.4f,%u,%.6e,%.6e,%.6e", p.seconds, p.spp, p.estimate.relMse, p.estimate.low,
                      p.estimate.high);
        out << line;
        if (withReference && p.reference) {
            const ReferenceMetrics& r = *p.reference;
            std::snprintf(line, sizeof line, ",%.6e,%.4f,%.6f,%.6f,%.6f", r.relMse, r.psnr, r.ssim, r.flipLdr, r.flipHdr);
            out << line;
        }
        out << "\n";
    }
    if (!out) throw std::runtime_error(file.string() + ": cannot write the report");
}

double RenderClock::seconds() const {
    const auto now = paused_ ? pausedAt_ : std::chrono::steady_clock::now();
    return std::chrono::duration<double>(now - start_).count() - excluded_;
}

void RenderClock::pause() {
    if (paused_) return;
    paused_ = true;
    pausedAt_ = std::chrono::steady_clock::now();
}

void RenderClock::resume() {
    if (!paused_) return;
    paused_ = false;
    excluded_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - pausedAt_).count();
}

}  // namespace ripple::apps
