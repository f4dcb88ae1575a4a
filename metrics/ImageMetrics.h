// Image comparison metrics shared by ripple-imgdiff, ripple-render's convergence report and the tests:
// relMSE, PSNR, SSIM and FLIP (LDR and HDR, after Andersson et al., "FLIP: A Difference Evaluator for
// Alternating Images", HPG 2020, and "Visualizing Errors in Rendered High Dynamic Range Images", EG 2021).
#pragma once

#include "io/image/LinearImage.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace ripple::apps {

// relMSE = mean over pixels and channels of (test - ref)^2 / (ref^2 + epsilon).
double relMse(const LinearImage& test, const LinearImage& reference, double epsilon = 1e-2);
// PSNR in dB of the sRGB-encoded images clamped to [0, 1] (peak 1); +infinity when they are equal.
double psnr(const LinearImage& test, const LinearImage& reference);
// Mean SSIM (Wang et al. 2004: 11x11 Gaussian window, sigma 1.5, K1 0.01, K2 0.03) of the luminance of the
// sRGB-encoded images clamped to [0, 1].
double ssim(const LinearImage& test, const LinearImage& reference);

// FLIP: the mean of the per-pixel error map (values in [0, 1]); the map is filled when asked for (row 0 at
// the top). LDR-FLIP takes linear values and clamps them to [0, 1], what a display shows; pixelsPerDegree
// defaults to the paper's 0.7 m viewing of a 0.7 m wide 3840-pixel monitor (0.7 * 3840 / 0.7 * pi / 180 =
// 67.02 px/deg, rounded to 67). Checked against the published algorithm: see README, "ripple-imgdiff".
double flipLdr(const LinearImage& test, const LinearImage& reference, std::vector<float>* errorMap = nullptr,
               double pixelsPerDegree = 67.0);
// HDR-FLIP: LDR-FLIP of ACES-tone-mapped exposures, the per-pixel maximum over them. The exposures run from the
// one that maps the reference's brightest luminance to 0.85 to the one that maps its median there,
// max(2, ceil(stop - start)) of them (detail::flipExposures).
double flipHdr(const LinearImage& test, const LinearImage& reference, std::vector<float>* errorMap = nullptr,
               double pixelsPerDegree = 67.0);

// Which of FLIP's measures a FlipReference is prepared for.
enum FlipModes : unsigned { kFlipLdr = 1, kFlipHdr = 2, kFlipBoth = 3 };

// FLIP of many images against one reference (a convergence series): the reference's side of LDR-FLIP and of
// every HDR-FLIP exposure (the perceived colours of its filtered planes, its feature responses) is computed
// once, here, instead of at every comparison. ldr() and hdr() give exactly flipLdr() and flipHdr() against the same reference.
class FlipReference {
public:
    explicit FlipReference(const LinearImage& reference, FlipModes modes = kFlipBoth, double pixelsPerDegree = 67.0);
    ~FlipReference();
    FlipReference(FlipReference&&) noexcept;
    FlipReference& operator=(FlipReference&&) noexcept;

    double ldr(const LinearImage& test, std::vector<float>* errorMap = nullptr) const;
    double hdr(const LinearImage& test, std::vector<float>* errorMap = nullptr) const;

    struct Side;  // one image as LDR-FLIP compares it (Flip.cpp)

private:
    void requireTest(const LinearImage& test, bool prepared, const char* metric) const;

    uint32_t width_ = 0, height_ = 0;
    double pixelsPerDegree_ = 67.0;
    std::vector<Side> ldrSide_;         // one, when prepared for LDR-FLIP
    std::vector<Side> hdrSides_;        // one per HDR-FLIP exposure
    std::vector<float> exposureScales_;  // each exposure's linear scale
};

}  // namespace ripple::apps
