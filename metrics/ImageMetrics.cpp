// relMSE, PSNR and SSIM, and the filtering helpers FLIP (Flip.cpp) shares with SSIM.
#include "metrics/ImageMetrics.h"

#include "metrics/ImageMetricsDetail.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ripple::apps {

namespace detail {

namespace {

std::string sizeText(uint32_t width, uint32_t height) { return std::to_string(width) + "x" + std::to_string(height); }

void requireThreeFloatsPerPixel(const LinearImage& image, const char* metric) {
    if (image.rgb.size() != size_t(image.width) * image.height * 3)
        throw std::invalid_argument(std::string(metric) + ": a " + sizeText(image.width, image.height) + " image holds " +
                                    std::to_string(image.rgb.size()) + " floats, not 3 per pixel");
}

}  // namespace

void requireComparable(const LinearImage& test, uint32_t referenceWidth, uint32_t referenceHeight, const char* metric) {
    if (test.width != referenceWidth || test.height != referenceHeight)
        throw std::invalid_argument(std::string(metric) + ": image sizes differ (test " + sizeText(test.width, test.height) +
                                    ", reference " + sizeText(referenceWidth, referenceHeight) + ")");
    if (test.width == 0 || test.height == 0) throw std::invalid_argument(std::string(metric) + ": the images are empty");
    requireThreeFloatsPerPixel(test, metric);
}

void requireComparable(const LinearImage& test, const LinearImage& reference, const char* metric) {
    requireComparable(test, reference.width, reference.height, metric);
    requireThreeFloatsPerPixel(reference, metric);
}

Plane convolveSeparable(const Plane& plane, const std::vector<float>& kernelX, const std::vector<float>& kernelY) {
    const int w = int(plane.width), h = int(plane.height);
    const int rx = int(kernelX.size() / 2), ry = int(kernelY.size() / 2);
    // Every output is one double sum (SSIM subtracts squares of these means, float sums would leave noise)
    // of its taps in kernel order, whatever the row or thread. Both passes add one tap to a whole run of
    // outputs at a time (the columns: whole rows; the rows: the pixels whose taps need no clamp), so the
    // sums of neighbouring outputs proceed side by side and memory is read in order. Rows run in parallel.
    Plane rows{plane.width, plane.height, std::vector<float>(plane.values.size())};
    const int interiorBegin = std::min(rx, w), interiorEnd = std::max(interiorBegin, w - rx);
    tbb::parallel_for(0, h, [&](int y) {
        const float* in = plane.values.data() + size_t(y) * size_t(w);
        std::vector<double> sums(size_t(w), 0.0);
        for (int k = -rx; k <= rx; ++k) {
            const double weight = kernelX[size_t(k + rx)];
            for (int x = interiorBegin; x < interiorEnd; ++x) sums[size_t(x)] += weight * in[x + k];
        }
        auto clampedSum = [&](int x) {
            for (int k = -rx; k <= rx; ++k) sums[size_t(x)] += double(kernelX[size_t(k + rx)]) * in[std::clamp(x + k, 0, w - 1)];
        };
        for (int x = 0; x < interiorBegin; ++x) clampedSum(x);
        for (int x = interiorEnd; x < w; ++x) clampedSum(x);
        float* out = rows.values.data() + size_t(y) * size_t(w);
        for (size_t x = 0; x < sums.size(); ++x) out[x] = float(sums[x]);
    });
    Plane result{plane.width, plane.height, std::vector<float>(plane.values.size())};
    tbb::parallel_for(0, h, [&](int y) {
        std::vector<double> sums(size_t(w), 0.0);
        for (int k = -ry; k <= ry; ++k) {
            const float* in = rows.values.data() + size_t(std::clamp(y + k, 0, h - 1)) * size_t(w);
            const double weight = kernelY[size_t(k + ry)];
            for (size_t x = 0; x < sums.size(); ++x) sums[x] += weight * in[x];
        }
        float* out = result.values.data() + size_t(y) * size_t(w);
        for (size_t x = 0; x < sums.size(); ++x) out[x] = float(sums[x]);
    });
    return result;
}

std::vector<float> gaussianKernel(float sigma, int radius) {
    std::vector<float> kernel(size_t(2 * radius + 1));
    float sum = 0;
    for (int x = -radius; x <= radius; ++x) sum += kernel[size_t(x + radius)] = std::exp(-float(x * x) / (2 * sigma * sigma));
    for (float& weight : kernel) weight /= sum;
    return kernel;
}

}  // namespace detail

namespace {

float encodedClamped(float linear) { return detail::srgbEncode(std::clamp(linear, 0.0f, 1.0f)); }

}  // namespace

double relMse(const LinearImage& test, const LinearImage& reference, double epsilon) {
    detail::requireComparable(test, reference, "relMSE");
    if (!(epsilon > 0)) throw std::invalid_argument("relMSE: epsilon must be positive");
    double sum = 0;
    for (size_t i = 0; i < test.rgb.size(); ++i) {
        const double difference = double(test.rgb[i]) - double(reference.rgb[i]);
        sum += difference * difference / (double(reference.rgb[i]) * reference.rgb[i] + epsilon);
    }
    return sum / double(test.rgb.size());
}

double psnr(const LinearImage& test, const LinearImage& reference) {
    detail::requireComparable(test, reference, "PSNR");
    double sum = 0;
    for (size_t i = 0; i < test.rgb.size(); ++i) {
        const double difference = double(encodedClamped(test.rgb[i])) - double(encodedClamped(reference.rgb[i]));
        sum += difference * difference;
    }
    const double mse = sum / double(test.rgb.size());
    return mse == 0 ? std::numeric_limits<double>::infinity() : -10.0 * std::log10(mse);
}

double ssim(const LinearImage& test, const LinearImage& reference) {
    detail::requireComparable(test, reference, "SSIM");
    auto luma = [](const LinearImage& image) {
        detail::Plane plane{image.width, image.height, std::vector<float>(size_t(image.width) * image.height)};
        for (size_t p = 0; p < plane.values.size(); ++p)
            plane.values[p] = 0.2126f * encodedClamped(image.rgb[p * 3]) + 0.7152f * encodedClamped(image.rgb[p * 3 + 1]) +
                              0.0722f * encodedClamped(image.rgb[p * 3 + 2]);
        return plane;
    };
    const detail::Plane x = luma(test), y = luma(reference);
    // Variances and the covariance are taken of the images less their global means: the same values in exact
    // arithmetic, but without float cancellation between E[x^2] and E[x]^2 (a constant image gets exactly 0).
    auto centred = [](const detail::Plane& plane) {
        double mean = 0;
        for (float v : plane.values) mean += v;
        mean /= double(plane.values.size());
        detail::Plane result = plane;
        for (float& v : result.values) v = float(v - mean);
        return result;
    };
    const detail::Plane cx = centred(x), cy = centred(y);
    detail::Plane xx = cx, yy = cy, xy = cx;
    for (size_t p = 0; p < x.values.size(); ++p) {
        xx.values[p] = cx.values[p] * cx.values[p];
        yy.values[p] = cy.values[p] * cy.values[p];
        xy.values[p] = cx.values[p] * cy.values[p];
    }
    const std::vector<float> window = detail::gaussianKernel(1.5f, 5);  // 11 taps
    auto blur = [&](const detail::Plane& plane) { return convolveSeparable(plane, window, window); };
    const detail::Plane meanX = blur(x), meanY = blur(y), meanCx = blur(cx), meanCy = blur(cy);
    const detail::Plane meanXX = blur(xx), meanYY = blur(yy), meanXY = blur(xy);
    const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;  // (K L)^2 with dynamic range L = 1
    double sum = 0;
    for (size_t p = 0; p < x.values.size(); ++p) {
        const double mx = meanX.values[p], my = meanY.values[p], mcx = meanCx.values[p], mcy = meanCy.values[p];
        const double varianceX = std::max(0.0, meanXX.values[p] - mcx * mcx);
        const double varianceY = std::max(0.0, meanYY.values[p] - mcy * mcy);
        const double covariance = meanXY.values[p] - mcx * mcy;
        sum += (2 * mx * my + c1) * (2 * covariance + c2) / ((mx * mx + my * my + c1) * (varianceX + varianceY + c2));
    }
    return sum / double(x.values.size());
}

}  // namespace ripple::apps
