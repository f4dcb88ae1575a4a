// Pieces the metrics share (ImageMetrics.cpp, Flip.cpp): size checks and separable convolution of
// one-channel planes; and FLIP's stages, exposed for the tests.
#pragma once

#include "metrics/ImageMetrics.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace ripple::apps::detail {

// Throws std::invalid_argument naming the metric and both sizes when the images differ in size or are empty.
void requireComparable(const LinearImage& test, const LinearImage& reference, const char* metric);
// The same for a test against a reference known by its size only (the reference checked before).
void requireComparable(const LinearImage& test, uint32_t referenceWidth, uint32_t referenceHeight, const char* metric);

// One channel of an image, row 0 at the top.
struct Plane {
    uint32_t width = 0, height = 0;
    std::vector<float> values;
    float& at(uint32_t x, uint32_t y) { return values[size_t(y) * width + x]; }
    float at(uint32_t x, uint32_t y) const { return values[size_t(y) * width + x]; }
};

// Convolves with kernelX along rows, then kernelY along columns (odd lengths, centred). Edges repeat the
// border pixel, so a constant plane stays exactly constant under a kernel that sums to one.
Plane convolveSeparable(const Plane& plane, const std::vector<float>& kernelX, const std::vector<float>& kernelY);

// exp(-x^2 / (2 sigma^2)) for x in [-radius, radius] pixels, scaled to sum to one.
std::vector<float> gaussianKernel(float sigma, int radius);

// FLIP's stages. flipCsfFilter: the contrast sensitivity filter of YCxCz channel 0 (achromatic), 1 (red-green)
// or 2 (blue-yellow). flipColourDistance: HyAB between the Hunt-adjusted Lab of two linear RGB colours.
// flipRedistributeColourError: that distance raised to q_c = 0.7 and mapped to [0, 1], p_c = 0.4 of the
// green-blue distance going to p_t = 0.95. flipToneMap: HDR-FLIP's ACES curve.
Plane flipCsfFilter(const Plane& plane, int channel, double pixelsPerDegree);
float flipColourDistance(const std::array<float, 3>& rgbA, const std::array<float, 3>& rgbB);
float flipRedistributeColourError(float hyabDistance);
float flipToneMap(float x);

// HDR-FLIP's exposures (log2 of the scale), derived from the reference: `start` maps its brightest luminance
// to 0.85 after tone mapping, `stop` its median; max(2, ceil(stop - start)) of them evenly spaced, or one
// where start equals stop.
struct FlipExposures {
    double start = 0, stop = 0;
    int count = 1;
};
FlipExposures flipExposures(const LinearImage& reference);

}  // namespace ripple::apps::detail
