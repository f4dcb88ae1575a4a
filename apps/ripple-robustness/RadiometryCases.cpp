// Robustness group "radiometry": light strengths from 1e-38 to 1e36 scale the image linearly, emissive
// triangles far smaller than a pixel still deliver their power, and an environment with a sun 1e6 times
// brighter than its sky converges to its analytic irradiance without NaN, Inf or many fireflies.
#include "apps/ripple-robustness/Robustness.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

namespace ripple::robustness {
namespace {

constexpr float kAlbedo = 0.5f;
constexpr double kPi = glm::pi<double>();
// The lit plane is z = 0; lights and emitters sit at z = 1; the orthographic camera looks down from
// z = 0.5, under the emitters, so camera rays meet only the plane (a camera ray hitting a tiny emitter
// would add noise, not information, to these cases).
constexpr float kLightHeight = 1.0f;
constexpr float kViewHeight = 2.0f;  // the camera sees x, y in [-1, 1]

std::string number(double value) { return formatNumber(value, 4); }

ANARISurface plane(Harness& harness, float halfSize) {
    const std::vector<glm::vec3> corners{{-halfSize, -halfSize, 0.0f}, {halfSize, -halfSize, 0.0f},
                                         {halfSize, halfSize, 0.0f}, {-halfSize, halfSize, 0.0f}};
    return harness.surface(harness.triangles(corners, {{0, 1, 2}, {0, 2, 3}}), harness.matte(glm::vec3(kAlbedo)));
}

ANARICamera cameraDown(Harness& harness, float z = 0.5f) {
    ANARIDevice d = harness.device();
    ANARICamera camera = harness.keep(anariNewCamera(d, "orthographic"));
    const glm::vec3 position(0.0f, 0.0f, z), direction(0.0f, 0.0f, -1.0f), up(0.0f, 1.0f, 0.0f);
    anariSetParameter(d, camera, "position", ANARI_FLOAT32_VEC3, &position);
    anariSetParameter(d, camera, "direction", ANARI_FLOAT32_VEC3, &direction);
    anariSetParameter(d, camera, "up", ANARI_FLOAT32_VEC3, &up);
    anariSetParameter(d, camera, "height", ANARI_FLOAT32, &kViewHeight);
    anariCommitParameters(d, camera);
    return camera;
}

// The mean over the camera's view of a radiance field on the plane (midpoint rule, 256 x 256 points).
double viewMean(const std::function<double(double, double)>& radiance) {
    constexpr int n = 256;
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            sum += radiance(kViewHeight * ((i + 0.5) / n - 0.5), kViewHeight * ((j + 0.5) / n - 0.5));
    return sum / (double(n) * n);
}

// Outgoing radiance of the matte plane at (x, y) lit by a Lambertian emitter at (cx, cy, kLightHeight)
// facing down, of intensity I along its normal: E = I cos(theta) cos(theta') / d^2 = I h^2 / d^4.
double underEmitter(double x, double y, double cx, double cy, double intensity) {
    const double h = kLightHeight, d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy) + h * h;
    return kAlbedo / kPi * intensity * h * h / (d2 * d2);
}

double meanOf(const Image& image) { return uniformity(image, 0.0f, INFINITY).mean; }

Row row(const std::string& name, const Image& image) {
    Row r;
    r.group = "radiometry";
    r.name = name;
    r.finite = image.nonFinite == 0;
    return r;
}

// --- light strength sweep ---

struct LightKind {
    const char* name;
    const char* amountParameter;
    std::function<ANARILight(Harness&, float)> make;
    std::function<double(double, double)> radianceAtUnitAmount;  // analytic, for amount 1
    double analyticTolerance;                                    // relative, for the amount-1 render
};

std::vector<LightKind> lightKinds() {
    constexpr float quadSize = 0.5f;
    return {
        {"directional", "irradiance",
         [](Harness& h, float amount) { return h.directional(glm::vec3(0.0f, 0.0f, -1.0f), amount); },
         [](double, double) { return kAlbedo / kPi; },
         // One deterministic shadow ray per sample: only float rounding differs.
         1e-4},
        {"point", "intensity",
         [](Harness& h, float amount) {
             ANARILight light = h.keep(anariNewLight(h.device(), "point"));
             const glm::vec3 position(0.0f, 0.0f, kLightHeight);
             anariSetParameter(h.device(), light, "position", ANARI_FLOAT32_VEC3, &position);
             anariSetParameter(h.device(), light, "intensity", ANARI_FLOAT32, &amount);
             anariCommitParameters(h.device(), light);
             return light;
         },
         [](double x, double y) {
             const double d2 = x * x + y * y + double(kLightHeight) * kLightHeight;
             return kAlbedo / kPi * kLightHeight / (d2 * std::sqrt(d2));
         },
         // Only the pixel jitter is random: the mean of a smooth field over 16 x 1024 samples.
         5e-3},
        {"quad", "radiance",
         [](Harness& h, float amount) {
             ANARILight light = h.keep(anariNewLight(h.device(), "quad"));
             // edge1 x edge2 points down, towards the plane.
             const glm::vec3 position(-0.5f * quadSize, 0.5f * quadSize, kLightHeight);
             const glm::vec3 edge1(quadSize, 0.0f, 0.0f), edge2(0.0f, -quadSize, 0.0f);
             anariSetParameter(h.device(), light, "position", ANARI_FLOAT32_VEC3, &position);
             anariSetParameter(h.device(), light, "edge1", ANARI_FLOAT32_VEC3, &edge1);
             anariSetParameter(h.device(), light, "edge2", ANARI_FLOAT32_VEC3, &edge2);
             anariSetParameter(h.device(), light, "radiance", ANARI_FLOAT32, &amount);
             anariCommitParameters(h.device(), light);
             return light;
         },
         [](double x, double y) {
             constexpr int n = 12;  // the quad as n x n small emitters
             const double cell = double(quadSize) / n;
             double sum = 0.0;
             for (int j = 0; j < n; ++j)
                 for (int i = 0; i < n; ++i)
                     sum += underEmitter(x, y, -0.5 * quadSize + (i + 0.5) * cell, -0.5 * quadSize + (j + 0.5) * cell,
                                         cell * cell);
             return sum;
         },
         // Light samples over the quad: 16 x 1024 samples of a smooth integrand, a few tenths of a percent.
         1e-2},
    };
}

void strengthSweep(Harness& harness, bool quick, std::vector<Row>& rows) {
    // The full sweep goes on past 1e-10 .. 1e10 to where float's range ends.
    std::vector<int> exponents;
    if (quick) exponents = {-10, 10};
    else {
        exponents = {-38, -36, -30, -20};
        for (int e = -10; e <= 10; ++e)
            if (e != 0) exponents.push_back(e);
        exponents.insert(exponents.end(), {20, 30, 36});  // 1e38 would make true pixel values past float's range
    }
    RenderSettings settings;
    settings.maxPathLength = 1;  // direct light only: the plane cannot see itself anyway
    const ANARISurface ground = plane(harness, 4.0f);
    const ANARICamera camera = cameraDown(harness);

    for (const LightKind& kind : lightKinds()) {
        auto render = [&](float amount) {
            return harness.render(harness.world({ground}, {}, {kind.make(harness, amount)}), camera, settings);
        };
        const Image unit = render(1.0f);
        const double unitMean = meanOf(unit);
        const double analytic = viewMean(kind.radianceAtUnitAmount);
        Row base = row(std::string(kind.name) + " light, " + kind.amountParameter + " 1, against analytic", unit);
        base.holds = unit.rendered && std::abs(unitMean / analytic - 1.0) <= kind.analyticTolerance;
        base.measured = "mean " + number(unitMean) + " (want " + number(analytic) + " +- " +
                        number(kind.analyticTolerance * 100.0) + "%)";
        base.why = unit.rendered ? "" : "not rendered";
        rows.push_back(base);

        for (int exponent : exponents) {
            const double amount = std::pow(10.0, exponent);
            const Image image = render(float(amount));
            const double ratio = meanOf(image) / (amount * unitMean);
            Row r = row(std::string(kind.name) + " light, " + kind.amountParameter + " 1e" + std::to_string(exponent), image);
            // The values a sample computes are the amount times factors between 1e-3 and 1e3 (albedo / pi,
            // cosines, 1 / d^2, the quad's area, 16 samples summed): while those stay inside float's normal range
            // (1.2e-38 .. 3.4e38) only rounding (about 1e-6 relative) separates the ratio from 1.
            constexpr double tolerance = 1e-4;
            r.expected = amount * 1e-3 >= double(std::numeric_limits<float>::min()) &&
                         amount * 1e3 <= double(std::numeric_limits<float>::max());
            r.holds = image.rendered && unit.rendered && std::abs(ratio - 1.0) <= tolerance;
            r.measured = std::string("mean / amount = (1 ") + (ratio < 1.0 ? "- " : "+ ") + number(std::abs(ratio - 1.0)) +
                         ") x mean at amount 1 (want 1 +- 1e-4)";
            r.why = r.expected ? (r.holds ? "" : "not linear in the light's strength")
                               : "amount x 1e-3 .. 1e3 leaves float's normal range (1.2e-38 .. 3.4e38): denormals "
                                 "flush to 0, or sums overflow to Inf";
            rows.push_back(r);
        }
    }
}

// --- emissive triangles far smaller than a pixel ---

ANARIMaterial emitterMaterial(Harness& harness, float radiance) {
    ANARIDevice d = harness.device();
    ANARIMaterial emitter = harness.keep(anariNewMaterial(d, "physicallyBased"));
    const glm::vec3 black(0.0f), emissive(radiance);
    anariSetParameter(d, emitter, "baseColor", ANARI_FLOAT32_VEC3, &black);
    anariSetParameter(d, emitter, "emissive", ANARI_FLOAT32_VEC3, &emissive);
    anariCommitParameters(d, emitter);
    return emitter;
}

// Seen directly: 4096 triangles of a fraction of a pixel's area, one in each pixel's area at a random place. Camera rays hit
// them by chance, each hit worth radiance / spp, so the mean over the frame is count x radiance x area /
// frame area, with the relative noise of a Poisson count of hits, 1 / sqrt(hits).
void emittersInView(Harness& harness, bool quick, std::vector<Row>& rows) {
    const std::vector<double> pixelFractions = quick ? std::vector<double>{1.0 / 16} : std::vector<double>{1.0 / 16, 1.0 / 100};
    constexpr uint32_t count = 4096;
    constexpr float radiance = 1.0f;
    RenderSettings settings;
    settings.size = {64, 64};
    settings.maxPathLength = 1;
    const double frameArea = double(kViewHeight) * kViewHeight;
    const double pixelArea = frameArea / (64.0 * 64.0);
    const ANARICamera camera = cameraDown(harness, 2.0f);
    for (double fraction : pixelFractions) {
        settings.pixelSamples = fraction < 0.05 ? 256 : 64;
        const double area = fraction * pixelArea;
        const float edge = float(std::sqrt(2.0 * area));
        std::vector<glm::vec3> positions;
        uint32_t state = 12345u;
        auto next = [&state] {
            state = state * 1664525u + 1013904223u;
            return float(state >> 8) / float(1u << 24);
        };
        // One triangle in each cell of a 64 x 64 grid over the view, at a random place inside it: they never
        // overlap (overlapping coplanar emitters would show less than their summed area).
        const float cell = kViewHeight / 64.0f;
        for (uint32_t i = 0; i < count; ++i) {
            const glm::vec3 corner(-0.5f * kViewHeight + cell * float(i % 64) + (cell - edge) * next(),
                                   -0.5f * kViewHeight + cell * float(i / 64) + (cell - edge) * next(), kLightHeight);
            positions.insert(positions.end(), {corner, corner + glm::vec3(edge, 0, 0), corner + glm::vec3(0, edge, 0)});
        }
        const ANARISurface lights = harness.surface(harness.triangles(positions, {}), emitterMaterial(harness, radiance));
        const Image image = harness.render(harness.world({lights}, {}, {}), camera, settings);
        const double hits = count * double(settings.pixelSamples) * fraction;
        const double analytic = count * double(radiance) * area / frameArea;
        const double tolerance = 5.0 / std::sqrt(hits);  // 5 standard deviations of the hit count
        const double mean = meanOf(image);
        Row r = row(std::to_string(count) + " emissive triangles of " + number(fraction) + " pixel, seen directly at " +
                        std::to_string(settings.pixelSamples) + " spp", image);
        r.holds = image.rendered && std::abs(mean / analytic - 1.0) <= tolerance;
        r.measured = "mean " + number(mean) + " (want " + number(analytic) + " +- " + number(tolerance * 100.0) +
                     "%, 5 sigma of " + number(hits) + " expected hits)";
        r.why = r.holds ? "" : "emitters smaller than a pixel lose or gain power";
        rows.push_back(r);
    }
}

void tinyEmitters(Harness& harness, bool quick, std::vector<Row>& rows) {
    const std::vector<double> areas = quick ? std::vector<double>{1e-4, 1e-10} : std::vector<double>{1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-16};
    constexpr double intensityEach = 0.25;  // W/sr along the normal, per triangle
    const glm::vec2 centers[4] = {{-0.25f, -0.25f}, {0.25f, -0.25f}, {-0.25f, 0.25f}, {0.25f, 0.25f}};
    const double pixelArea = double(kViewHeight) * kViewHeight / (64.0 * 64.0);
    RenderSettings settings;
    settings.size = {64, 64};
    settings.maxPathLength = 1;
    const ANARISurface ground = plane(harness, 4.0f);
    const ANARICamera camera = cameraDown(harness);

    for (double area : areas) {
        const float edge = float(std::sqrt(2.0 * area));
        std::vector<glm::vec3> positions;
        for (glm::vec2 c : centers) {
            positions.emplace_back(c.x, c.y, kLightHeight);
            positions.emplace_back(c.x + edge, c.y, kLightHeight);
            positions.emplace_back(c.x, c.y + edge, kLightHeight);
        }
        // Radiance so that each triangle of the intended area sends intensityEach; the analytic mean uses the
        // intended area, so rounding of the vertices shows.
        const float radiance = float(intensityEach / area);
        const ANARISurface lights = harness.surface(harness.triangles(positions, {}), emitterMaterial(harness, radiance));
        const Image image = harness.render(harness.world({ground, lights}, {}, {}), camera, settings);

        const double analytic = viewMean([&](double x, double y) {
            double sum = 0.0;
            for (glm::vec2 c : centers) sum += underEmitter(x, y, c.x, c.y, intensityEach);
            return sum;
        });
        const double mean = meanOf(image);
        // Vertices near 0.25 round by half an ulp (1.5e-8) each, so the area is off by up to 2 x 1.5e-8 / edge;
        // with light sampling noise of about 0.5% (4 lights, 16 x 4096 samples), 2% holds while that is <= 1%.
        const double halfUlp = 0.5 * double(std::nextafter(0.25f, 1.0f) - 0.25f);
        const double areaError = 2.0 * halfUlp / std::sqrt(2.0 * area);
        constexpr double tolerance = 0.02;
        Row r = row("4 emissive triangles of area " + number(area) + " (" + number(area / pixelArea) +
                        " pixel) lighting a plane", image);
        r.expected = areaError <= 0.01;
        r.holds = image.rendered && std::abs(mean / analytic - 1.0) <= tolerance;
        r.measured = "mean " + number(mean) + " (want " + number(analytic) + " +- 2%)";
        r.why = r.expected ? "" : "edge " + number(edge) + " is " + number(edge / (2.0 * halfUlp)) +
                                      " ulps of its position 0.25: the area rounds by up to " + number(areaError * 100.0) + "%";
        rows.push_back(r);
    }
}

// --- an HDR environment with a sun ---

void sunAndSky(Harness& harness, bool quick, std::vector<Row>& rows) {
    const std::vector<double> sunRatios = quick ? std::vector<double>{1e6} : std::vector<double>{1e3, 1e6, 1e9};
    constexpr uint32_t width = 64, height = 32, sunColumn = 20, sunRow = 8;  // the sun 45..50.6 degrees from the zenith
    RenderSettings settings;
    settings.pixelSamples = 16;
    settings.maxPathLength = 1;
    const ANARISurface ground = plane(harness, 4.0f);
    const ANARICamera camera = cameraDown(harness);

    for (double sun : sunRatios) {
        std::vector<glm::vec3> texels(size_t(width) * height, glm::vec3(1.0f));
        texels[size_t(sunRow) * width + sunColumn] = glm::vec3(float(sun));
        ANARIDevice d = harness.device();
        ANARIArray2D radiance = harness.keep(anariNewArray2D(d, nullptr, nullptr, nullptr, ANARI_FLOAT32_VEC3, width, height));
        std::memcpy(anariMapArray(d, radiance), texels.data(), texels.size() * sizeof(glm::vec3));
        anariUnmapArray(d, radiance);
        ANARILight hdri = harness.keep(anariNewLight(d, "hdri"));
        const glm::vec3 direction(1.0f, 0.0f, 0.0f), up(0.0f, 0.0f, 1.0f);
        anariSetParameter(d, hdri, "radiance", ANARI_ARRAY2D, &radiance);
        anariSetParameter(d, hdri, "direction", ANARI_FLOAT32_VEC3, &direction);
        anariSetParameter(d, hdri, "up", ANARI_FLOAT32_VEC3, &up);
        anariCommitParameters(d, hdri);
        const Image image = harness.render(harness.world({ground}, {}, {hdri}), camera, settings);

        // Row r spans polar angles r pi/H .. (r+1) pi/H from "up" (the plane's normal), each texel 2 pi / W of
        // azimuth: its irradiance is L (2 pi / W) (sin^2 theta1 - sin^2 theta0) / 2. Rows below the horizon
        // do not reach the plane's top.
        double irradiance = 0.0;
        for (uint32_t r = 0; r < height / 2; ++r) {
            const double s0 = std::sin(kPi * r / height), s1 = std::sin(kPi * (r + 1) / height);
            for (uint32_t c = 0; c < width; ++c)
                irradiance += double(texels[size_t(r) * width + c].x) * (2.0 * kPi / width) * (s1 * s1 - s0 * s0) / 2.0;
        }
        const double analytic = kAlbedo / kPi * irradiance;
        const double mean = meanOf(image);

        std::vector<float> luminance;
        for (const glm::vec4& p : image.rgba) luminance.push_back((p.x + p.y + p.z) / 3.0f);
        uint64_t fireflies = 0;
        if (!luminance.empty()) {
            std::vector<float> sorted = luminance;
            std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
            const float median = sorted[sorted.size() / 2];
            fireflies = uint64_t(std::count_if(luminance.begin(), luminance.end(), [&](float l) { return l > 10.0f * median; }));
        }
        // The sun's texel is sampled by luminance, so each sample's estimate varies only with cos(theta) across
        // one texel (a few percent): 16 x 1024 samples bring the mean within 2%.
        constexpr double tolerance = 0.02;
        Row r = row("hdri sky 1 with a one-texel sun " + number(sun) + " x brighter", image);
        r.holds = image.rendered && std::abs(mean / analytic - 1.0) <= tolerance;
        r.measured = "mean " + number(mean) + " (want " + number(analytic) + " +- 2%), " + std::to_string(fireflies) +
                     " of " + std::to_string(luminance.size()) + " pixels above 10 x median";
        r.why = r.holds ? "" : "environment sampling misses the analytic irradiance";
        rows.push_back(r);
    }
}

}  // namespace

std::vector<Row> radiometryCases(Harness& harness, bool quick) {
    std::vector<Row> rows;
    strengthSweep(harness, quick, rows);
    tinyEmitters(harness, quick, rows);
    emittersInView(harness, quick, rows);
    sunAndSky(harness, quick, rows);
    return rows;
}

}  // namespace ripple::robustness
