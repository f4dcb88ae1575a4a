// The no-reference error estimate of ripple-render: the half-buffer estimator against an analytic variance on
// synthetic samples, and a real render of the Cornell demo against a converged reference, where the estimate
// must track the true relMSE and the true relMSE must fall as about 1/spp (the path tracer is unbiased; the
// stratified pixel jitter and first bounce can make it a little steeper).
//
// The reference, tests/apps/references/cornell-48x48.pfm, was rendered once with
//   ripple-render --demo cornell --size 48x48 --spp 2048 -o cornell-48x48.pfm
// (3 minutes on two loaded CPU cores with lavapipe). Its own noise is 1/2048 of a sample's variance per
// pixel: at the 64 spp the test reaches that adds 64/2048 = 3% to the true relMSE, well inside the margins.
#include "apps/ripple-render/Convergence.h"
#include "tests/apps/ProgramRun.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

using namespace ripple::test;
using ripple::apps::HalfBufferEstimator;

namespace {

constexpr uint32_t kWidth = 64, kHeight = 64;

// Per-pixel true values between 0.5 and 2.5 (alpha 1), bottom row first like a mapped frame: a smooth ramp,
// or detail at the scale of a pixel (neighbours along a row differ by 0.22).
std::vector<double> trueImage(bool pixelScaleDetail) {
    std::vector<double> mu(size_t(kWidth) * kHeight * 4);
    for (size_t p = 0; p < size_t(kWidth) * kHeight; ++p)
        for (size_t c = 0; c < 4; ++c) {
            const size_t x = p % kWidth, y = p / kWidth;
            const double ramp = double(x + y + 8 * c) / double(kWidth + kHeight + 22);
            mu[p * 4 + c] = c == 3 ? 1.0 : pixelScaleDetail ? 0.5 + 2.0 * double((p * 7 + c * 13) % 64) / 64.0
                                                           : 0.5 + 2.0 * ramp;
        }
    return mu;
}

// relMSE a mean of n samples of standard deviation sigma has in expectation: Var = sigma^2 / n.
double expectedRelMse(const std::vector<double>& mu, double sigma, uint32_t n) {
    double total = 0.0;
    for (size_t p = 0; p < size_t(kWidth) * kHeight; ++p)
        for (size_t c = 0; c < 3; ++c) total += sigma * sigma / n / (mu[p * 4 + c] * mu[p * 4 + c] + ripple::apps::kRelMseEpsilon);
    return total / double(kWidth * kHeight * 3);
}

// Feeds `batches` one-sample batches of mu + Gaussian noise to the estimator, as an accumulating device maps
// them (float running averages) or as a device that does not accumulate (each frame alone).
void feed(HalfBufferEstimator& estimator, const std::vector<double>& mu, double sigma, uint32_t batches,
          bool accumulated) {
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, sigma);
    std::vector<double> sum(mu.size(), 0.0);
    std::vector<float> frame(mu.size());
    for (uint32_t k = 1; k <= batches; ++k) {
        for (size_t i = 0; i < mu.size(); ++i) {
            const double sample = mu[i] + (i % 4 == 3 ? 0.0 : noise(rng));
            sum[i] += sample;
            frame[i] = float(accumulated ? sum[i] / k : sample);
        }
        if (accumulated) estimator.addAccumulatedFrame(frame.data(), k);
        else estimator.addBatchFrame(frame.data(), 1);
    }
}

}  // namespace

// 12,288 pixel channels each give a one-degree-of-freedom estimate of their variance (relative spread
// sqrt(2)), so the mean is within about 1.3% of the expectation; on a smooth image 5% still fails a wrong
// variance factor such as a missing /4 (unequal halves are checked exactly below). Where the image has
// detail at the scale of a pixel the neighbours' median stands in for mu only as far as the clamp to the
// pixel's own [min(A, B), max(A, B)] lets it, and that clamp ties the denominator to the numerator: the
// estimate is low there, measured by 7.5% (64 and 63 samples) and 10% (16 samples); 15% bounds it.
TEST_CASE("half-buffer estimate matches the analytic relMSE of synthetic samples") {
    constexpr double sigma = 0.3;
    for (const bool detail : {false, true}) {
        const std::vector<double> mu = trueImage(detail);
        for (const uint32_t batches : {64u, 63u, 16u}) {  // equal halves, unequal halves, fewer samples
            for (const bool accumulated : {true, false}) {
                CAPTURE(detail);
                CAPTURE(batches);
                CAPTURE(accumulated);
                HalfBufferEstimator estimator(kWidth, kHeight);
                feed(estimator, mu, sigma, batches, accumulated);
                CHECK(estimator.samples() == batches);
                CHECK(estimator.batches() == batches);
                const double ratio = estimator.estimatedRelMse() / expectedRelMse(mu, sigma, batches);
                CAPTURE(ratio);
                CHECK(std::abs(ratio - 1.0) < (detail ? 0.15 : 0.05));
            }
        }
    }
}

TEST_CASE("half-buffer estimator: recovered mean, too few batches, restarted accumulation") {
    HalfBufferEstimator estimator(2, 1);
    CHECK(std::isnan(estimator.estimatedRelMse()));
    const float first[8] = {1, 2, 3, 1, 0, 0, 0, 1};
    estimator.addAccumulatedFrame(first, 2);
    CHECK(std::isnan(estimator.estimatedRelMse()));  // one half still empty
    const float second[8] = {2, 2, 3, 1, 1, 0, 0, 1};  // averages of 4 samples
    estimator.addAccumulatedFrame(second, 4);
    // Pixel 0: half A sums 2, 4, 6 (mean 1, 2, 3), half B 8 - 2 = 6, 4, 6 (mean 3, 2, 3): red gives
    // (A - B)^2 / 4 = 1 over m^2 + 0.01, m = its one neighbour's red mean 1 (clamped to [A, B] = [1, 3]): 1.01.
    // Pixel 1: red A 0, B 2: 1 over 2^2 + 0.01 (pixel 0's red mean 2, inside [0, 2]). The rest differ by 0.
    CHECK(std::abs(estimator.estimatedRelMse() / ((1.0 / 1.01 + 1.0 / 4.01) / 6.0) - 1.0) < 1e-6);
    const std::vector<double> map = estimator.errorMap();
    REQUIRE(map.size() == 2);
    CHECK(map[0] == doctest::Approx(1.0 / 1.01 / 3.0));
    CHECK(map[1] == doctest::Approx(1.0 / 4.01 / 3.0));
    const std::vector<float> mean = estimator.meanRgbaBottomUp();
    for (size_t i = 0; i < 8; ++i) CHECK(mean[i] == doctest::Approx(second[i]).epsilon(1e-6));
    CHECK(estimator.meanImage().at(1, 0, 0) == doctest::Approx(1.0));
    CHECK_THROWS_WITH_AS(estimator.addAccumulatedFrame(first, 4),
                         "the device's sample count went from 4 to 4: it restarted its accumulation", std::runtime_error);
}

// A firefly: one sample 1000 times the pixel's mean (0.5) in a smooth, noisy image, as a rare light path
// gives. The estimate must follow the image's own squared error against the known mean, which the firefly
// dominates (about 94% of it): within 15%. The earlier denominator A B took the firefly into mu^2 and came
// out 16 times too low here; F^2 is worse.
TEST_CASE("half-buffer estimate follows a firefly") {
    const std::vector<double> mu(size_t(kWidth) * kHeight * 4, 0.5);
    constexpr uint32_t batches = 32;
    constexpr size_t fireflyPixel = 1000;
    std::mt19937 rng(11);
    std::normal_distribution<double> noise(0.0, 0.1);
    HalfBufferEstimator estimator(kWidth, kHeight);
    std::vector<double> sum(mu.size(), 0.0);
    std::vector<float> frame(mu.size());
    for (uint32_t k = 1; k <= batches; ++k) {
        for (size_t i = 0; i < mu.size(); ++i) {
            double sample = i % 4 == 3 ? 1.0 : mu[i] + noise(rng);
            if (k == 5 && i / 4 == fireflyPixel && i % 4 != 3) sample += 500.0;
            sum[i] += sample;
            frame[i] = float(sum[i] / k);
        }
        estimator.addAccumulatedFrame(frame.data(), k);
    }
    double realised = 0.0;  // the image's relMSE against the true mean
    for (size_t p = 0; p < size_t(kWidth) * kHeight; ++p)
        for (size_t c = 0; c < 3; ++c) {
            const double error = sum[p * 4 + c] / batches - mu[p * 4 + c];
            realised += error * error / (mu[p * 4 + c] * mu[p * 4 + c] + ripple::apps::kRelMseEpsilon);
        }
    realised /= double(kWidth * kHeight * 3);
    CAPTURE(realised);
    CHECK(std::abs(estimator.estimatedRelMse() / realised - 1.0) < 0.15);
    // The map puts it where it is (row 0 at the top; the sums are bottom row first).
    const std::vector<double> map = estimator.errorMap();
    const size_t x = fireflyPixel % kWidth, y = kHeight - 1 - fireflyPixel / kWidth;
    CHECK(map[y * kWidth + x] > 0.9 * realised * double(kWidth * kHeight));
}

// Three one-sample batches of red 1, 4, 1 (green, blue, alpha 1): half A holds two (mean 1), half B one
// (mean 4), so Var(F) = (A - B)^2 * 2 / 9 = 2 over F^2 + 0.01 = 4.01 (no neighbours: the full mean 2 stands
// for mu), averaged over 3 channels.
TEST_CASE("half-buffer estimate with unequal halves") {
    HalfBufferEstimator estimator(1, 1);
    const float means[3][4] = {{1, 1, 1, 1}, {2.5f, 1, 1, 1}, {2, 1, 1, 1}};
    for (uint32_t k = 0; k < 3; ++k) estimator.addAccumulatedFrame(means[k], k + 1);
    CHECK(std::abs(estimator.estimatedRelMse() / (2.0 / 4.01 / 3.0) - 1.0) < 1e-6);
}

TEST_CASE("report points lie about 1.2 times apart, at every power of two") {
    std::vector<uint32_t> spp{2};
    while (spp.back() < 128) spp.push_back(ripple::apps::nextReportSpp(spp.back()));
    CHECK(spp == std::vector<uint32_t>{2, 3, 4, 5, 6, 7, 8, 10, 12, 14, 16, 19, 23, 28, 32, 38, 46, 55, 64, 77, 92,
                                       110, 128});
}

// The real thing: 64 spp of the 48x48 Cornell demo, one sample per frame, reported at 19 points, rendered
// with seeds 1 to 4 (the reference's seed is 0: an image must not share samples with the reference that
// judges it). At each point the estimates and the true relMSEs are summed over the four runs.
// (a) The estimated relMSE is within a factor 2 of the true relMSE at every point, and within a factor 1.25
//     from 4 spp on (measured: 0.97 to 1.09 from 4 spp on, 1.15 at 2 and 3 spp; one seed alone, over seeds
//     1 to 8 at 4, 6, 8, 16 and 64 spp, before the cosine share in very rough lobes: 0.87 to 1.17). Each
//     run's band holds its true relMSE at every point (checked too).
// (b) The least-squares slope of log(true relMSE) against log(spp) is -1 within 0.15 (a sample costs the
//     same time throughout, so this is the slope against time without the noise of a shared machine's
//     clock): error falls as 1/time for this unbiased renderer (measured: -1.10; the stratified pixel
//     jitter and first bounce make it a little steeper). The renders are deterministic (fixed sample
//     seeds), so these numbers repeat run to run.
TEST_CASE("the estimate tracks the true relMSE, which falls as 1/spp") {
    const int seeds = 4;
    std::vector<double> spps, estimates, truths;
    std::ostringstream table;  // shown when a check fails
    for (int seed = 1; seed <= seeds; ++seed) {
        TempFolder dir;
        const auto report = dir / "series.csv";
        const ProgramRun run = runRender("--demo cornell --size 48x48 --spp 64 --quiet --seed " + std::to_string(seed) +
                                         " --reference '" + RIPPLE_TEST_REFERENCES + "/cornell-48x48.pfm' --report '" +
                                         report.string() + "' -o '" + (dir / "c.pfm").string() + "'");
        REQUIRE_MESSAGE(run.exitCode == 0, run.output);
        const auto rows = readCsv(report);
        REQUIRE(rows.size() == 20);  // header, spp 2 .. 64 (19 points)
        REQUIRE(rows[0].size() == 10);
        spps.resize(rows.size() - 1);
        estimates.resize(rows.size() - 1);
        truths.resize(rows.size() - 1);
        for (size_t i = 1; i < rows.size(); ++i) {
            const double spp = std::stod(rows[i][1]), estimate = std::stod(rows[i][2]), truth = std::stod(rows[i][5]);
            table << "seed " << seed << ", " << spp << " spp: estimated " << estimate << ", true " << truth << "\n";
            CHECK_MESSAGE(std::stod(rows[i][3]) <= truth, "seed " << seed << ", spp " << spp);  // band_low
            CHECK_MESSAGE(std::stod(rows[i][4]) >= truth, "seed " << seed << ", spp " << spp);  // band_high
            spps[i - 1] = spp;
            estimates[i - 1] += estimate;
            truths[i - 1] += truth;
        }
    }
    INFO(table.str());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const int n = int(spps.size());
    for (int i = 0; i < n; ++i) {
        const double factor = spps[i] >= 4 ? 1.25 : 2.0;
        CHECK_MESSAGE(estimates[i] <= factor * truths[i], "spp " << spps[i]);
        CHECK_MESSAGE(estimates[i] >= truths[i] / factor, "spp " << spps[i]);
        const double x = std::log(spps[i]), y = std::log(truths[i] / seeds);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    CAPTURE(slope);
    CHECK(std::abs(slope + 1.0) < 0.15);
}

// Calibration against an independently seeded reference: each shared scene (and the default demo) at 64x64,
// 128 spp with seed 2 reported at 8, 32 and 128 spp, against a stored reference of 4096 spp with seed 1,
// tests/apps/references/calibration-SCENE.pfm, rendered once (SCENE: the file, or --demo default) with
//   ripple-render SCENE --size 64x64 --spp 4096 --seed 1 -o calibration-SCENE.pfm
// (39 to 82 s each on two CPU cores with lavapipe; rendering a 1024-spp one in every run took 86 of this
// suite's seconds). Render them again when a change moves the renderer's mean on these scenes: this test then
// fails, as it should. The reference's own noise adds Var(F) n / 4096 to the measured relMSE in expectation,
// so the true relMSE of the image is taken as the measured one divided by 1 + n / 4096. Checked: (a) the band
// holds the true relMSE on every scene at every one of these spp; (b) on the scenes without highlights
// smaller than a pixel (the Cornell box, the bunny, Sponza, the default demo) the estimate itself is within
// 35% (measured 0.84 to 1.28; docs/error-estimate.md has the metallic scenes, where the estimate is up to 27
// times high at 8 spp and the band says so). Fixed seeds: the numbers repeat run to run.
TEST_CASE("sample files: the error estimate is calibrated against an independently seeded reference") {
    struct Scene { std::string arguments; std::string name; bool subPixelHighlights; };
    const std::string data = std::string(RIPPLE_DATA_DIR) + "/gltf/";
    const std::vector<Scene> scenes{{"'" + data + "cornell-box.glb'", "cornell-box", false},
                                    {"'" + data + "bunny.glb'", "bunny", false},
                                    {"'" + data + "sponza-lod4-geometry.glb'", "sponza-lod4-geometry", false},
                                    {"--demo default", "demo-default", false},
                                    {"'" + data + "damaged-helmet.glb'", "damaged-helmet", true},
                                    {"'" + data + "metal-rough-spheres.glb'", "metal-rough-spheres", true}};
    constexpr double kReferenceSpp = 4096;
    for (const Scene& scene : scenes) {
        CAPTURE(scene.arguments);
        TempFolder dir;
        const std::string reference = std::string(RIPPLE_TEST_REFERENCES) + "/calibration-" + scene.name + ".pfm";
        const auto report = dir / "series.csv";
        const ProgramRun run = runRender(scene.arguments + " --size 64x64 --spp 128 --seed 2 --quiet --reference '" +
                                         reference + "' --report '" + report.string() + "' -o '" +
                                         (dir / "image.pfm").string() + "'");
        REQUIRE_MESSAGE(run.exitCode == 0, run.output);
        int checked = 0;
        for (const auto& row : readCsv(report)) {
            if (row[1] != "8" && row[1] != "32" && row[1] != "128") continue;
            const double spp = std::stod(row[1]), estimate = std::stod(row[2]), low = std::stod(row[3]),
                         high = std::stod(row[4]), truth = std::stod(row[5]) / (1.0 + spp / kReferenceSpp);
            INFO("spp " << spp << ": estimated " << estimate << " (band " << low << " .. " << high << "), true " << truth);
            CHECK(low <= truth);
            CHECK(truth <= high);
            if (!scene.subPixelHighlights) CHECK(std::abs(estimate / truth - 1.0) <= 0.35);
            ++checked;
        }
        CHECK(checked == 3);
    }
}
