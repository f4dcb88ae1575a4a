// FLIP, written from the papers named in ImageMetrics.h: LDR-FLIP compares two images as a viewer at a given
// number of pixels per degree would see them (colour after contrast sensitivity filtering, plus edges and
// points); HDR-FLIP runs LDR-FLIP on tone-mapped exposures spanning the reference and keeps the worst.
#include "metrics/ImageMetrics.h"

#include "metrics/ImageMetricsDetail.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace ripple::apps {

namespace {

using detail::Plane;
using Vec3 = std::array<float, 3>;

// Runs body(p) for every pixel index p in [0, count), spread over the cores (each pixel is independent).
template <class Body>
void forEachPixel(size_t count, const Body& body) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 1024), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t p = range.begin(); p != range.end(); ++p) body(p);
    });
}

// Linear sRGB (D65) <-> CIE XYZ with the matrix FLIP publishes (its entries are exact fractions; the inverse is
// given to ten digits), so that Ripple's Lab and YCxCz values are FLIP's own.
Vec3 linearRgbToXyz(const Vec3& c) {
    return {(10135552.0f * c[0] + 8788810.0f * c[1] + 4435075.0f * c[2]) / 24577794.0f,
            (2613072.0f * c[0] + 8788810.0f * c[1] + 887015.0f * c[2]) / 12288897.0f,
            (1425312.0f * c[0] + 8788810.0f * c[1] + 70074185.0f * c[2]) / 73733382.0f};
}

Vec3 xyzToLinearRgb(const Vec3& c) {
    return {3.241003275f * c[0] - 1.537398934f * c[1] - 0.498615861f * c[2],
            -0.969224334f * c[0] + 1.875930071f * c[1] + 0.041554224f * c[2],
            0.055639423f * c[0] - 0.204011202f * c[1] + 1.057148933f * c[2]};
}

// FLIP's D65 reference white, so linear RGB (1, 1, 1) maps to Yy = 100 and Cx, Cz within 1e-4 of 0.
constexpr Vec3 kWhite = {0.950428545f, 1.0f, 1.088900371f};

// YCxCz: the opponent space in which FLIP applies its contrast sensitivity functions (achromatic, red-green,
// blue-yellow). Linear in XYZ, so filtering there is filtering of light.
Vec3 xyzToYcxcz(const Vec3& c) {
    const float x = c[0] / kWhite[0], y = c[1] / kWhite[1], z = c[2] / kWhite[2];
    return {116 * y - 16, 500 * (x - y), 200 * (y - z)};
}

Vec3 ycxczToXyz(const Vec3& c) {
    const float y = (c[0] + 16) / 116, x = y + c[1] / 500, z = y - c[2] / 200;
    return {x * kWhite[0], y * kWhite[1], z * kWhite[2]};
}

Vec3 xyzToLab(const Vec3& c) {
    constexpr float delta = 6.0f / 29.0f;
    auto f = [](float t) { return t > delta * delta * delta ? std::cbrt(t) : t / (3 * delta * delta) + 4.0f / 29.0f; };
    const float fx = f(c[0] / kWhite[0]), fy = f(c[1] / kWhite[1]), fz = f(c[2] / kWhite[2]);
    return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

// Hunt effect: colourfulness grows with lightness, so chroma is scaled by L / 100.
Vec3 huntAdjust(const Vec3& lab) { return {lab[0], 0.01f * lab[0] * lab[1], 0.01f * lab[0] * lab[2]}; }

// HyAB: city-block in lightness, Euclidean in chroma; better than Euclidean Lab for large differences.
float hyab(const Vec3& a, const Vec3& b) {
    return std::abs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

constexpr float kQc = 0.7f, kPc = 0.4f, kPt = 0.95f, kQf = 0.5f;
// Edge width the feature detectors look for, in degrees of visual angle.
constexpr float kFeatureWidth = 0.082f;

struct YcxczPlanes {
    std::array<Plane, 3> channels;
};

YcxczPlanes toYcxcz(const LinearImage& image) {
    YcxczPlanes planes;
    for (Plane& plane : planes.channels) plane = Plane{image.width, image.height, std::vector<float>(size_t(image.width) * image.height)};
    for (size_t p = 0; p < planes.channels[0].values.size(); ++p) {
        const Vec3 ycxcz = xyzToYcxcz(linearRgbToXyz({image.rgb[p * 3], image.rgb[p * 3 + 1], image.rgb[p * 3 + 2]}));
        for (int c = 0; c < 3; ++c) planes.channels[size_t(c)].values[p] = ycxcz[size_t(c)];
    }
    return planes;
}

// The spatial contrast sensitivity filter of one opponent channel: a sum of two Gaussians whose published
// parameters (a1, b1, a2, b2) are in cycles-per-degree units; x is the distance in degrees.
//   S(x) = a1 sqrt(pi / b1) exp(-pi^2 x^2 / b1) + a2 sqrt(pi / b2) exp(-pi^2 x^2 / b2), normalised to sum 1.
// Each Gaussian is separable, so the filter is the weighted sum of two separable convolutions.
struct CsfParameters {
    float a1, b1, a2, b2;
};
constexpr std::array<CsfParameters, 3> kCsf = {{{1.0f, 0.0047f, 0.0f, 1e-5f},       // achromatic
                                                 {1.0f, 0.0053f, 0.0f, 1e-5f},       // red-green
                                                 {34.1f, 0.04f, 13.5f, 0.025f}}};  // blue-yellow

Plane csfFilter(const Plane& plane, const CsfParameters& csf, double pixelsPerDegree) {
    constexpr float pi = std::numbers::pi_v<float>;
    // Radius: three standard deviations of the widest Gaussian of all three channels (b = 0.04), as FLIP does, so
    // every channel's kernel has the same size (21 taps at 67 px/deg).
    const float widest = std::sqrt(0.04f / (2 * pi * pi));
    const int radius = int(std::ceil(3 * widest * float(pixelsPerDegree)));
    std::array<std::vector<float>, 2> kernels;
    std::array<double, 2> mass{};
    const std::array<std::array<float, 2>, 2> terms = {{{csf.a1, csf.b1}, {csf.a2, csf.b2}}};
    for (size_t t = 0; t < 2; ++t) {
        kernels[t].resize(size_t(2 * radius + 1));
        double sum = 0;
        for (int i = -radius; i <= radius; ++i) {
            const float degrees = float(i) / float(pixelsPerDegree);
            sum += kernels[t][size_t(i + radius)] = std::exp(-pi * pi * degrees * degrees / terms[t][1]);
        }
        for (float& weight : kernels[t]) weight = float(weight / sum);
        mass[t] = double(terms[t][0]) * std::sqrt(pi / terms[t][1]) * sum * sum;  // the term's 2D kernel sum
    }
    Plane result = convolveSeparable(plane, kernels[0], kernels[0]);
    if (mass[1] == 0) return result;
    const Plane second = convolveSeparable(plane, kernels[1], kernels[1]);
    const float w0 = float(mass[0] / (mass[0] + mass[1])), w1 = 1 - w0;
    for (size_t p = 0; p < result.values.size(); ++p) result.values[p] = w0 * result.values[p] + w1 * second.values[p];
    return result;
}

// The Hunt-adjusted Lab colour of each pixel of CSF-filtered YCxCz planes: what the colour error compares.
std::vector<Vec3> perceivedColours(const std::array<Plane, 3>& filtered) {
    std::vector<Vec3> colours(filtered[0].values.size());
    forEachPixel(colours.size(), [&](size_t p) {
        Vec3 rgb = xyzToLinearRgb(ycxczToXyz({filtered[0].values[p], filtered[1].values[p], filtered[2].values[p]}));
        for (float& v : rgb) v = std::clamp(v, 0.0f, 1.0f);  // filtering may leave the gamut
        colours[p] = huntAdjust(xyzToLab(linearRgbToXyz(rgb)));
    });
    return colours;
}

}  // namespace

// Edge (first derivative) and point (second derivative) responses of Gaussians of the feature width, on the
// UNFILTERED YCxCz luminance normalised to [0, 1] as (Yy + 16) / 116, as FLIP does. Each derivative kernel's positive weights sum to 1 and its negative
// weights to -1, so a step from 0 to 1 gives an edge response near 1. (Outside the anonymous namespace:
// FlipReference::Side holds them.)
namespace detail {
struct FeatureResponses {
    std::vector<float> edge, point;
};
}  // namespace detail

namespace {

using detail::FeatureResponses;

FeatureResponses features(const YcxczPlanes& image, double pixelsPerDegree) {
    const float sigma = 0.5f * kFeatureWidth * float(pixelsPerDegree);
    const int radius = int(std::ceil(3 * sigma));
    const std::vector<float> gaussian = detail::gaussianKernel(sigma, radius);
    std::vector<float> first(gaussian.size()), second(gaussian.size());
    for (int i = -radius; i <= radius; ++i) {
        const float x = float(i), g = gaussian[size_t(i + radius)];
        first[size_t(i + radius)] = -x * g;
        second[size_t(i + radius)] = (x * x / (sigma * sigma) - 1) * g;
    }
    auto normaliseSigns = [](std::vector<float>& kernel) {
        float positive = 0, negative = 0;
        for (float w : kernel) (w > 0 ? positive : negative) += w;
        for (float& w : kernel) w = w > 0 ? w / positive : w < 0 ? w / -negative : 0.0f;
    };
    normaliseSigns(first);
    normaliseSigns(second);

    Plane luminance = image.channels[0];
    for (float& v : luminance.values) v = (v + 16) / 116;
    const Plane edgeX = convolveSeparable(luminance, first, gaussian), edgeY = convolveSeparable(luminance, gaussian, first);
    const Plane pointX = convolveSeparable(luminance, second, gaussian), pointY = convolveSeparable(luminance, gaussian, second);
    FeatureResponses responses{std::vector<float>(luminance.values.size()), std::vector<float>(luminance.values.size())};
    forEachPixel(luminance.values.size(), [&](size_t p) {
        responses.edge[p] = std::hypot(edgeX.values[p], edgeY.values[p]);
        responses.point[p] = std::hypot(pointX.values[p], pointY.values[p]);
    });
    return responses;
}

}  // namespace

// One image as LDR-FLIP compares it (linear values already in [0, 1]): the perceived colours of its YCxCz
// planes filtered by the contrast sensitivity functions, and its edge and point responses.
struct FlipReference::Side {
    std::vector<Vec3> perceived;  // Hunt-adjusted Lab of the CSF-filtered image
    FeatureResponses features;
};

namespace {

FlipReference::Side flipSide(const LinearImage& image, double pixelsPerDegree) {
    const YcxczPlanes planes = toYcxcz(image);
    std::array<Plane, 3> filtered;
    for (size_t c = 0; c < 3; ++c) filtered[c] = detail::flipCsfFilter(planes.channels[c], int(c), pixelsPerDegree);
    FlipReference::Side side;
    side.perceived = perceivedColours(filtered);
    side.features = features(planes, pixelsPerDegree);
    return side;
}

// The LDR-FLIP map of two prepared images. The colour error: HyAB of the perceived colours, raised to q_c
// and redistributed so that the p_c fraction of the largest possible error (green against blue) covers
// [0, p_t]; edges and points that differ then raise it toward 1.
std::vector<float> ldrErrorMap(const FlipReference::Side& test, const FlipReference::Side& reference) {
    std::vector<float> error(test.perceived.size());
    forEachPixel(error.size(), [&](size_t p) {
        const float colourError = detail::flipRedistributeColourError(hyab(test.perceived[p], reference.perceived[p]));
        const float featureDifference = std::max(std::abs(reference.features.edge[p] - test.features.edge[p]),
                                                 std::abs(reference.features.point[p] - test.features.point[p]));
        const float featureError = std::pow(std::min(featureDifference / std::numbers::sqrt2_v<float>, 1.0f), kQf);
        // Features raise the colour error toward 1 (the exponent shrinks) where edges or points differ.
        error[p] = std::pow(colourError, 1 - featureError);
    });
    return error;
}

template <typename Transform>
LinearImage transformed(const LinearImage& image, Transform transform) {
    LinearImage result = image;
    for (float& v : result.rgb) {
        v = transform(v);
        v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
    }
    return result;
}

double meanOf(const std::vector<float>& map) {
    double sum = 0;
    for (float v : map) sum += v;
    return sum / double(map.size());
}

void requirePixelsPerDegree(double pixelsPerDegree) {
    if (!(pixelsPerDegree > 0 && pixelsPerDegree < 1e4))
        throw std::invalid_argument("FLIP: pixels per degree must be in (0, 10000), not " + std::to_string(pixelsPerDegree));
}

// ACES filmic curve (Narkowicz's fit) with HDR-FLIP's 0.6 pre-exposure cancelled into its coefficients:
// t(x) = (a x^2 + b x) / (c x^2 + d x + e).
constexpr float kAcesA = 0.6f * 0.6f * 2.51f, kAcesB = 0.6f * 0.03f, kAcesC = 0.6f * 0.6f * 2.43f,
                kAcesD = 0.6f * 0.59f, kAcesE = 0.14f;

// HDR-FLIP's view of a linear value at one exposure: scaled, then ACES tone-mapped (as a transformed() transform).
auto toneMappedBy(float scale) {
    return [scale](float v) { return detail::flipToneMap(std::max(v, 0.0f) * scale); };
}

// The input the tone mapper maps to `target` (the positive root of a quadratic).
float acesInverse(float target) {
    const float a = kAcesA - target * kAcesC, b = kAcesB - target * kAcesD, c = -target * kAcesE;
    return (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
}

}  // namespace

namespace detail {

Plane flipCsfFilter(const Plane& plane, int channel, double pixelsPerDegree) {
    if (channel < 0 || channel > 2) throw std::invalid_argument("FLIP: CSF channel must be 0, 1 or 2, not " + std::to_string(channel));
    return csfFilter(plane, kCsf[size_t(channel)], pixelsPerDegree);
}

float flipColourDistance(const std::array<float, 3>& rgbA, const std::array<float, 3>& rgbB) {
    return hyab(huntAdjust(xyzToLab(linearRgbToXyz(rgbA))), huntAdjust(xyzToLab(linearRgbToXyz(rgbB))));
}

float flipRedistributeColourError(float hyabDistance) {
    static const float largest = std::pow(flipColourDistance({0, 1, 0}, {0, 0, 1}), kQc);
    const float e = std::pow(hyabDistance, kQc), knee = kPc * largest;
    const float redistributed = e < knee ? kPt / knee * e : kPt + (e - knee) / (largest - knee) * (1 - kPt);
    // FLIP leaves this unclamped; only a pair further apart than green and blue could exceed 1.
    return std::min(redistributed, 1.0f);
}

float flipToneMap(float x) {
    if (std::isinf(x)) return 1.0f;
    return (kAcesA * x * x + kAcesB * x) / (kAcesC * x * x + kAcesD * x + kAcesE);
}

FlipExposures flipExposures(const LinearImage& reference) {
    std::vector<float> luminance(size_t(reference.width) * reference.height);
    for (size_t p = 0; p < luminance.size(); ++p) {
        const float y = 0.2126f * reference.rgb[p * 3] + 0.7152f * reference.rgb[p * 3 + 1] + 0.0722f * reference.rgb[p * 3 + 2];
        luminance[p] = std::isfinite(y) ? std::max(y, 0.0f) : 0.0f;
    }
    const float brightest = *std::max_element(luminance.begin(), luminance.end());
    if (brightest <= 0) return {0, 0, 1};  // a black reference: FLIP uses the single exposure 0
    // The median as FLIP's C++ tool takes it: the element at index n / 2 (the upper middle one for even n).
    std::nth_element(luminance.begin(), luminance.begin() + ptrdiff_t(luminance.size() / 2), luminance.end());
    const float median = luminance[luminance.size() / 2];
    // FLIP's stop exposure is infinite when over half the reference is black; twenty stops below the
    // brightest pixel bound it instead.
    const float darkest = std::max(median, brightest * 0x1p-20f);
    const float mapsTo085 = acesInverse(0.85f);
    FlipExposures exposures{std::log2(mapsTo085 / brightest), std::log2(mapsTo085 / darkest), 1};
    if (exposures.stop > exposures.start) exposures.count = std::max(2, int(std::ceil(exposures.stop - exposures.start)));
    return exposures;
}

}  // namespace detail

FlipReference::FlipReference(const LinearImage& reference, FlipModes modes, double pixelsPerDegree)
    : width_(reference.width), height_(reference.height), pixelsPerDegree_(pixelsPerDegree) {
    requirePixelsPerDegree(pixelsPerDegree);
    detail::requireComparable(reference, reference, modes == kFlipHdr ? "HDR-FLIP" : "FLIP");
    if (modes & kFlipLdr) ldrSide_.push_back(flipSide(transformed(reference, [](float v) { return v; }), pixelsPerDegree));
    if (modes & kFlipHdr) {
        const detail::FlipExposures exposures = detail::flipExposures(reference);
        for (int i = 0; i < exposures.count; ++i) {
            const double exposure = exposures.start + (exposures.stop - exposures.start) * i / std::max(exposures.count - 1, 1);
            const float scale = float(std::exp2(exposure));
            exposureScales_.push_back(scale);
            hdrSides_.push_back(flipSide(transformed(reference, toneMappedBy(scale)), pixelsPerDegree));
        }
    }
}

FlipReference::~FlipReference() = default;
FlipReference::FlipReference(FlipReference&&) noexcept = default;
FlipReference& FlipReference::operator=(FlipReference&&) noexcept = default;

void FlipReference::requireTest(const LinearImage& test, bool prepared, const char* metric) const {
    if (!prepared) throw std::logic_error(std::string(metric) + ": the FlipReference was not prepared for it");
    detail::requireComparable(test, width_, height_, metric);
}

double FlipReference::ldr(const LinearImage& test, std::vector<float>* errorMap) const {
    requireTest(test, !ldrSide_.empty(), "FLIP");
    std::vector<float> map = ldrErrorMap(flipSide(transformed(test, [](float v) { return v; }), pixelsPerDegree_), ldrSide_[0]);
    const double mean = meanOf(map);
    if (errorMap) *errorMap = std::move(map);
    return mean;
}

double FlipReference::hdr(const LinearImage& test, std::vector<float>* errorMap) const {
    requireTest(test, !hdrSides_.empty(), "HDR-FLIP");
    std::vector<float> map(size_t(width_) * height_, 0.0f);
    for (size_t i = 0; i < hdrSides_.size(); ++i) {
        const std::vector<float> exposureMap =
            ldrErrorMap(flipSide(transformed(test, toneMappedBy(exposureScales_[i])), pixelsPerDegree_), hdrSides_[i]);
        for (size_t p = 0; p < map.size(); ++p) map[p] = std::max(map[p], exposureMap[p]);
    }
    const double mean = meanOf(map);
    if (errorMap) *errorMap = std::move(map);
    return mean;
}

double flipLdr(const LinearImage& test, const LinearImage& reference, std::vector<float>* errorMap,
               double pixelsPerDegree) {
    return FlipReference(reference, kFlipLdr, pixelsPerDegree).ldr(test, errorMap);
}

double flipHdr(const LinearImage& test, const LinearImage& reference, std::vector<float>* errorMap,
               double pixelsPerDegree) {
    return FlipReference(reference, kFlipHdr, pixelsPerDegree).hdr(test, errorMap);
}

}  // namespace ripple::apps
