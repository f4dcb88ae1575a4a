// Image metrics against values known in closed form: relMSE of a constant offset, PSNR of a known sRGB error,
// SSIM of equal and of constant images, FLIP's range and ordering, and FLIP's stages against values worked out
// by hand (in double precision) from the published formulas and constants; the magma heat-map colours.
#include "metrics/HeatMap.h"
#include "metrics/ImageMetrics.h"
#include "metrics/ImageMetricsDetail.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using ripple::apps::LinearImage;

namespace {

LinearImage constant(uint32_t width, uint32_t height, float value) {
    return LinearImage{width, height, std::vector<float>(size_t(width) * height * 3, value)};
}

// A smooth colour ramp with a sharp bar: colour, edges and points for FLIP to see.
LinearImage pattern(uint32_t size) {
    LinearImage image = constant(size, size, 0);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            float* p = &image.rgb[(size_t(y) * size + x) * 3];
            p[0] = float(x) / float(size);
            p[1] = float(y) / float(size);
            p[2] = (x / 4 + y / 4) % 2 ? 0.8f : 0.1f;
        }
    return image;
}

LinearImage withNoise(const LinearImage& image, float amplitude, uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    LinearImage noisy = image;
    for (float& v : noisy.rgb) v = std::clamp(v + amplitude * uniform(random), 0.0f, 1.0f);
    return noisy;
}

float srgbEncode(float v) { return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f; }

}  // namespace

TEST_CASE("relMSE of a constant offset is offset^2 / (ref^2 + epsilon)") {
    const LinearImage reference = constant(7, 5, 0.5f), test = constant(7, 5, 0.75f);
    CHECK(ripple::apps::relMse(test, reference) == doctest::Approx(0.0625 / (0.25 + 0.01)).epsilon(1e-6));
    CHECK(ripple::apps::relMse(test, reference, 0.25) == doctest::Approx(0.0625 / 0.5).epsilon(1e-6));
    CHECK(ripple::apps::relMse(reference, reference) == 0.0);
}

TEST_CASE("PSNR of a known sRGB error, infinite for equal images") {
    // Linear values chosen so that the sRGB-encoded difference is 0.1 in every channel: MSE 0.01, PSNR 20 dB.
    const float encodedReference = 0.5f, encodedTest = 0.6f;
    auto decode = [](float e) { return std::pow((e + 0.055f) / 1.055f, 2.4f); };
    const LinearImage reference = constant(4, 4, decode(encodedReference)), test = constant(4, 4, decode(encodedTest));
    CHECK(srgbEncode(decode(0.6f)) == doctest::Approx(0.6f));
    CHECK(ripple::apps::psnr(test, reference) == doctest::Approx(20.0).epsilon(1e-4));
    CHECK(std::isinf(ripple::apps::psnr(reference, reference)));
    // Values beyond [0, 1] are clamped before encoding: 5 and 1 look the same.
    CHECK(std::isinf(ripple::apps::psnr(constant(3, 3, 5.0f), constant(3, 3, 1.0f))));
}

TEST_CASE("SSIM: 1 for equal images, (2ab + C1) / (a^2 + b^2 + C1) for constant images a and b") {
    const LinearImage image = pattern(24);
    CHECK(ripple::apps::ssim(image, image) == doctest::Approx(1.0).epsilon(1e-6));
    // Constant images have no variance, so SSIM reduces to its luminance term (C1 = 0.01^2).
    const float a = 0.3f, b = 0.7f;
    const LinearImage test = constant(16, 16, a), reference = constant(16, 16, b);
    const double ea = srgbEncode(a), eb = srgbEncode(b), c1 = 1e-4;
    CHECK(ripple::apps::ssim(test, reference) == doctest::Approx((2 * ea * eb + c1) / (ea * ea + eb * eb + c1)).epsilon(1e-5));
    CHECK(ripple::apps::ssim(withNoise(image, 0.2f, 1), image) < 0.9);
}

// SSIM against a direct evaluation of Wang et al.'s definition in double precision: at every pixel the
// 11x11 Gaussian window (sigma 1.5, normalised, edges clamped) gives the means, variances and covariance
// of the sRGB-encoded luminance, and the map is averaged. A window of another size or sigma, or constants
// other than (0.01)^2 and (0.03)^2, give other values on this textured, noisy pair.
TEST_CASE("SSIM equals a direct evaluation of its definition on a textured pair") {
    const LinearImage reference = pattern(23), test = withNoise(reference, 0.15f, 7);
    const int width = 23, height = 23, radius = 5;
    std::vector<double> weight(2 * radius + 1);
    double total = 0;
    for (int i = -radius; i <= radius; ++i) total += weight[size_t(i + radius)] = std::exp(-0.5 * i * i / (1.5 * 1.5));
    for (double& w : weight) w /= total;
    const auto luma = [](const LinearImage& image, int x, int y) {
        const float* p = &image.rgb[(size_t(y) * size_t(23) + size_t(x)) * 3];
        const auto e = [](float v) { return double(srgbEncode(std::clamp(v, 0.0f, 1.0f))); };
        return 0.2126 * e(p[0]) + 0.7152 * e(p[1]) + 0.0722 * e(p[2]);
    };
    double sum = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
            for (int j = -radius; j <= radius; ++j)
                for (int i = -radius; i <= radius; ++i) {
                    const double w = weight[size_t(i + radius)] * weight[size_t(j + radius)];
                    const int sx = std::clamp(x + i, 0, width - 1), sy = std::clamp(y + j, 0, height - 1);
                    const double a = luma(test, sx, sy), b = luma(reference, sx, sy);
                    mx += w * a;
                    my += w * b;
                    xx += w * a * a;
                    yy += w * b * b;
                    xy += w * a * b;
                }
            const double c1 = 1e-4, c2 = 9e-4;
            sum += (2 * mx * my + c1) * (2 * (xy - mx * my) + c2) /
                   ((mx * mx + my * my + c1) * (xx - mx * mx + yy - my * my + c2));
        }
    const double expected = sum / (width * height);
    MESSAGE("SSIM " << ripple::apps::ssim(test, reference) << ", direct " << expected);
    CHECK(expected < 0.9);
    CHECK(ripple::apps::ssim(test, reference) == doctest::Approx(expected).epsilon(1e-4));
}

// HDR-FLIP keeps each pixel's worst exposure: a reference at 0.01 but for a quarter at 100, and a test whose
// bright quarter is twice as bright. The exposures run from the one that shows 100 below white to the one
// that shows the median, 0.01, there; in the later ones both bright quarters are white and look alike, so
// only the maximum over the exposures sees the error, and the dark part, equal in both, stays unseen.
TEST_CASE("HDR-FLIP: each pixel's error is its worst over the exposures") {
    const uint32_t size = 32;
    LinearImage reference = constant(size, size, 0.01f), test = constant(size, size, 0.01f);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 3 * size / 4; x < size; ++x)
            for (uint32_t c = 0; c < 3; ++c) {
                reference.rgb[(size_t(y) * size + x) * 3 + c] = 100.0f;
                test.rgb[(size_t(y) * size + x) * 3 + c] = 200.0f;
            }
    REQUIRE(ripple::apps::detail::flipExposures(reference).count > 10);
    std::vector<float> map;
    ripple::apps::flipHdr(test, reference, &map);
    REQUIRE(map.size() == size_t(size) * size);
    double bright = 0, dark = 0;  // means away from the edge between them
    for (uint32_t y = 0; y < size; ++y) {
        for (uint32_t x = 0; x < size / 2; ++x) dark += map[size_t(y) * size + x];
        for (uint32_t x = 3 * size / 4 + 2; x < size; ++x) bright += map[size_t(y) * size + x];
    }
    bright /= double(size * (size / 4 - 2));
    dark /= double(size * size / 2);
    MESSAGE("HDR-FLIP over the bright quarter " << bright << ", the dark half " << dark);
    CHECK(bright > 0.1);
    CHECK(dark < 1e-3);
}

TEST_CASE("metrics refuse images of different sizes, naming both") {
    const LinearImage a = constant(4, 4, 0), b = constant(4, 5, 0);
    CHECK_THROWS_WITH(ripple::apps::relMse(a, b), doctest::Contains("4x4"));
    CHECK_THROWS_WITH(ripple::apps::psnr(a, b), doctest::Contains("4x5"));
    CHECK_THROWS_WITH(ripple::apps::ssim(a, b), doctest::Contains("sizes differ"));
    CHECK_THROWS_WITH(ripple::apps::flipLdr(a, b), doctest::Contains("sizes differ"));
    CHECK_THROWS_WITH(ripple::apps::flipHdr(a, b), doctest::Contains("sizes differ"));
    CHECK_THROWS_WITH(ripple::apps::flipLdr(a, a, nullptr, 0.0), doctest::Contains("pixels per degree"));
}

TEST_CASE("FLIP is 0 for equal images, its map lies in [0, 1], black against white is near 1") {
    const LinearImage image = pattern(32);
    std::vector<float> map;
    CHECK(ripple::apps::flipLdr(image, image, &map) == 0.0);
    CHECK(map.size() == size_t(32 * 32));
    CHECK(ripple::apps::flipHdr(image, image) == 0.0);

    const LinearImage noisy = withNoise(image, 0.3f, 7);
    for (auto* flip : {&ripple::apps::flipLdr, &ripple::apps::flipHdr}) {
        const double mean = flip(noisy, image, &map, 67.0);
        CHECK(mean > 0.0);
        CHECK(*std::min_element(map.begin(), map.end()) >= 0.0f);
        CHECK(*std::max_element(map.begin(), map.end()) <= 1.0f);
    }
    // Black against white: a lightness difference of 100 alone, which the redistribution puts at about 0.97.
    const double blackWhite = ripple::apps::flipLdr(constant(16, 16, 0), constant(16, 16, 1));
    CHECK(blackWhite > 0.9);
    CHECK(blackWhite <= 1.0);
}

TEST_CASE("FLIP grows with noise amplitude") {
    const LinearImage image = pattern(32);
    double previousLdr = 0, previousHdr = 0;
    for (float amplitude : {0.02f, 0.05f, 0.1f, 0.2f, 0.4f}) {
        const LinearImage noisy = withNoise(image, amplitude, 3);
        const double ldr = ripple::apps::flipLdr(noisy, image), hdr = ripple::apps::flipHdr(noisy, image);
        CAPTURE(amplitude);
        CHECK(ldr > previousLdr);
        CHECK(hdr > previousHdr);
        previousLdr = ldr;
        previousHdr = hdr;
    }
}

TEST_CASE("HDR-FLIP sees errors in highlights that LDR-FLIP clamps away") {
    // Both images are white or brighter everywhere: LDR-FLIP sees two white images; HDR-FLIP exposes down.
    LinearImage reference = constant(16, 16, 4.0f), test = reference;
    for (size_t i = 0; i < test.rgb.size() / 2; ++i) test.rgb[i] = 8.0f;
    CHECK(ripple::apps::flipLdr(test, reference) == 0.0);
    CHECK(ripple::apps::flipHdr(test, reference) > 0.05);
}

// A reference prepared once (a convergence series) judges each image as a fresh comparison does, in any
// order and as often as asked; a test of another size, or a measure it was not prepared for, is refused.
TEST_CASE("FlipReference: one prepared reference gives every image its own FLIP, and refuses what does not fit") {
    LinearImage reference = pattern(40);
    for (float& v : reference.rgb) v *= 3.0f;  // past 1, so HDR-FLIP has several exposures
    const std::vector<LinearImage> tests{withNoise(reference, 0.3f, 1), withNoise(reference, 0.05f, 2), reference,
                                         constant(40, 40, 0.5f)};
    const ripple::apps::FlipReference prepared(reference);
    for (int round = 0; round < 2; ++round)
        for (size_t i = 0; i < tests.size(); ++i) {
            CAPTURE(i);
            std::vector<float> map, freshMap;
            CHECK(prepared.ldr(tests[i], &map) == ripple::apps::flipLdr(tests[i], reference, &freshMap));
            CHECK(map == freshMap);
            CHECK(prepared.hdr(tests[i], &map) == ripple::apps::flipHdr(tests[i], reference, &freshMap));
            CHECK(map == freshMap);
        }
    CHECK(prepared.ldr(reference) == 0.0);
    CHECK(prepared.hdr(tests[0]) > prepared.hdr(tests[1]));
    CHECK_THROWS_WITH_AS(prepared.ldr(constant(40, 41, 0.5f)), doctest::Contains("sizes differ"), std::invalid_argument);
    const ripple::apps::FlipReference ldrOnly(reference, ripple::apps::kFlipLdr);
    CHECK_THROWS_WITH_AS(ldrOnly.hdr(tests[0]), doctest::Contains("not prepared"), std::logic_error);
}

// The expected values below come from evaluating FLIP's published formulas in double precision: the sRGB->XYZ
// matrix and D65 white FLIP uses, CIE Lab, the Hunt adjustment (chroma * L / 100), HyAB, q_c = 0.7, p_c = 0.4,
// p_t = 0.95, the CSF (a1, b1, a2, b2) = (1, 0.0047, 0, -), (1, 0.0053, 0, -), (34.1, 0.04, 13.5, 0.025) and the
// ACES fit with its 0.6 pre-exposure. Tolerances allow float rounding only (relative 1e-4 unless stated).

TEST_CASE("FLIP colour pipeline: HyAB of Hunt-adjusted Lab and the redistribution, by hand") {
    using ripple::apps::detail::flipColourDistance, ripple::apps::detail::flipRedistributeColourError;
    // Green against blue is FLIP's largest error: 203.3017, redistributed to exactly 1.
    CHECK(flipColourDistance({0, 1, 0}, {0, 0, 1}) == doctest::Approx(203.30165).epsilon(1e-5));
    CHECK(flipRedistributeColourError(203.30165f) == doctest::Approx(1.0).epsilon(1e-5));
    // Black against white: lightness 100 alone, 100^0.7 past the knee: 0.95 + 0.05 (...) = 0.967380.
    CHECK(flipColourDistance({0, 0, 0}, {1, 1, 1}) == doctest::Approx(100.0).epsilon(1e-5));
    CHECK(flipRedistributeColourError(100.0f) == doctest::Approx(0.9673798).epsilon(1e-5));
    // The knee: the distance whose 0.7th power is p_c of the largest (54.91047) maps to p_t = 0.95.
    CHECK(flipRedistributeColourError(54.910473f) == doctest::Approx(0.95).epsilon(1e-5));
    // Red against half red: lightness and Hunt-scaled chroma both differ.
    CHECK(flipColourDistance({1, 0, 0}, {0.5f, 0, 0}) == doctest::Approx(37.618843).epsilon(1e-4));
}

TEST_CASE("LDR-FLIP of uniform pairs is the redistributed colour distance (no features, CSF keeps constants)") {
    // 0.5 against 0.25 grey: HyAB 18.99384, redistributed 0.4518496; red against half red 0.7290357.
    CHECK(ripple::apps::flipLdr(constant(24, 24, 0.5f), constant(24, 24, 0.25f)) == doctest::Approx(0.4518496).epsilon(1e-4));
    LinearImage red = constant(24, 24, 0), halfRed = red;
    for (size_t p = 0; p < red.rgb.size(); p += 3) red.rgb[p] = 1, halfRed.rgb[p] = 0.5f;
    CHECK(ripple::apps::flipLdr(halfRed, red) == doctest::Approx(0.7290357).epsilon(1e-4));
    CHECK(ripple::apps::flipLdr(constant(16, 16, 0), constant(16, 16, 1)) == doctest::Approx(0.9673798).epsilon(1e-4));
}

TEST_CASE("FLIP's CSF filters: every channel's kernel spans the widest radius, 10 pixels at 67 px/deg") {
    // The impulse response of a normalised 2D kernel is the kernel: its taps worked out by hand.
    ripple::apps::detail::Plane impulse{31, 31, std::vector<float>(31 * 31, 0.0f)};
    impulse.at(15, 15) = 1;
    struct Expected {
        int channel;
        double centre, oneRight, fiveDiagonal, tenRight;
    };
    for (const Expected& e : {Expected{0, 0.14890264, 0.09327025, 1.0349994e-11, 7.1941214e-22},
                              Expected{1, 0.13204574, 0.08720960, 1.2963434e-10, 1.2726698e-19},
                              Expected{2, 0.020012847, 0.018737465, 9.3616498e-4, 5.5697770e-5}}) {
        CAPTURE(e.channel);
        const auto response = ripple::apps::detail::flipCsfFilter(impulse, e.channel, 67.0);
        // Ratios, since doctest's Approx tolerance is absolute for values far below 1.
        CHECK(response.at(15, 15) / e.centre == doctest::Approx(1.0).epsilon(1e-4));
        CHECK(response.at(16, 15) / e.oneRight == doctest::Approx(1.0).epsilon(1e-4));
        CHECK(response.at(20, 20) / e.fiveDiagonal == doctest::Approx(1.0).epsilon(1e-3));
        CHECK(response.at(25, 15) / e.tenRight == doctest::Approx(1.0).epsilon(1e-3));
        CHECK(response.at(26, 15) == 0.0f);  // radius ceil(3 sqrt(0.04 / (2 pi^2)) 67) = 10 for every channel
        double sum = 0;
        for (float v : response.values) sum += v;
        CHECK(sum == doctest::Approx(1.0).epsilon(1e-5));
    }
    CHECK_THROWS_WITH(ripple::apps::detail::flipCsfFilter(impulse, 3, 67.0), doctest::Contains("channel"));
}

TEST_CASE("HDR-FLIP's ACES curve and exposure range, by hand") {
    using ripple::apps::detail::flipExposures, ripple::apps::detail::flipToneMap;
    // t(1) = (0.36 * 2.51 + 0.018) / (0.36 * 2.43 + 0.354 + 0.14); t maps 2.1188723 to 0.85.
    CHECK(flipToneMap(1.0f) == doctest::Approx(0.67329047).epsilon(1e-5));
    CHECK(flipToneMap(2.1188723f) == doctest::Approx(0.85).epsilon(1e-5));
    CHECK(flipToneMap(std::numeric_limits<float>::infinity()) == 1.0f);
    // Grey luminances 1, 2, 3, 40: start maps the brightest (40) to 0.85, stop the median, the element at
    // n / 2 = 2 in sorted order (3), as FLIP's C++ tool takes it; ceil(log2(40 / 3)) = 4 exposures.
    LinearImage reference = constant(2, 2, 0);
    const float greys[] = {2, 40, 1, 3};
    for (size_t p = 0; p < 4; ++p) std::fill_n(&reference.rgb[p * 3], 3, greys[p]);
    const auto exposures = flipExposures(reference);
    CHECK(exposures.start == doctest::Approx(std::log2(2.1188723 / 40)).epsilon(1e-5));
    CHECK(exposures.stop == doctest::Approx(std::log2(2.1188723 / 3)).epsilon(1e-5));
    CHECK(exposures.count == 4);
    // A uniform reference has start = stop and a black one start = stop = 0: one exposure each.
    const auto uniform = flipExposures(constant(3, 3, 0.5f));
    CHECK(uniform.start == doctest::Approx(std::log2(2.1188723 / 0.5)).epsilon(1e-5));
    CHECK(uniform.count == 1);
    const auto black = flipExposures(constant(3, 3, 0.0f));
    CHECK((black.start == 0 && black.stop == 0 && black.count == 1));
}

TEST_CASE("heat maps use magma's 256 published colours, the nearest entry to value * 255") {
    using ripple::apps::magma;
    using Rgb = std::array<uint8_t, 3>;
    CHECK(magma(0.0f) == Rgb{0, 0, 4});          // entry 0: (0.001462, 0.000466, 0.013866)
    CHECK(magma(0.25f) == Rgb{81, 18, 124});     // entry 64: (0.316654, 0.071690, 0.485380)
    CHECK(magma(0.45185f) == Rgb{161, 48, 126}); // entry 115: (0.632805, 0.187893, 0.495332)
    CHECK(magma(1.0f) == Rgb{252, 253, 191});    // entry 255: (0.987053, 0.991438, 0.749504)
    CHECK(magma(std::nanf("")) == magma(0.0f));
    CHECK(magma(7.0f) == magma(1.0f));
}

// convolveSeparable against the plain definition: rows then columns, each output the double sum of its taps
// in kernel order with border pixels repeated. Equal bit for bit, on a non-square plane, with kernels
// shorter than the plane, as long as it and longer.
TEST_CASE("convolveSeparable equals the clamped two-pass convolution bit for bit") {
    using ripple::apps::detail::Plane;
    std::mt19937 random(7);
    std::uniform_real_distribution<float> uniform(-1.0f, 2.0f);
    Plane plane{37, 23, std::vector<float>(size_t(37) * 23)};
    for (float& v : plane.values) v = uniform(random);
    auto kernelOf = [&](size_t taps) {
        std::vector<float> kernel(taps);
        for (float& w : kernel) w = uniform(random);
        return kernel;
    };
    auto direct = [](const Plane& in, const std::vector<float>& kx, const std::vector<float>& ky) {
        const int w = int(in.width), h = int(in.height), rx = int(kx.size() / 2), ry = int(ky.size() / 2);
        Plane rows = in, out = in;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                double sum = 0;
                for (int k = -rx; k <= rx; ++k) sum += double(kx[size_t(k + rx)]) * in.at(uint32_t(std::clamp(x + k, 0, w - 1)), uint32_t(y));
                rows.at(uint32_t(x), uint32_t(y)) = float(sum);
            }
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                double sum = 0;
                for (int k = -ry; k <= ry; ++k) sum += double(ky[size_t(k + ry)]) * rows.at(uint32_t(x), uint32_t(std::clamp(y + k, 0, h - 1)));
                out.at(uint32_t(x), uint32_t(y)) = float(sum);
            }
        return out;
    };
    for (auto [tx, ty] : {std::pair<size_t, size_t>{1, 1}, {5, 9}, {21, 3}, {37, 47}, {81, 61}}) {
        CAPTURE(tx);
        CAPTURE(ty);
        const std::vector<float> kx = kernelOf(tx), ky = kernelOf(ty);
        const Plane fast = ripple::apps::detail::convolveSeparable(plane, kx, ky), slow = direct(plane, kx, ky);
        REQUIRE(fast.values.size() == slow.values.size());
        size_t differing = 0;
        for (size_t p = 0; p < fast.values.size(); ++p) differing += fast.values[p] != slow.values[p];
        CHECK(differing == 0);
    }
}
