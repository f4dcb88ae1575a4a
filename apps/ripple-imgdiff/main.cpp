// ripple-imgdiff: compares a test image with a reference (PNG, EXR or PFM, any mix) and prints PSNR, SSIM,
// relMSE, LDR-FLIP and HDR-FLIP; optionally writes them as JSON and a heat map of where they differ.
#include "io/FileWrite.h"
#include "io/image/ImageIO.h"
#include "metrics/HeatMap.h"
#include "metrics/ImageMetrics.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {

struct Options {
    std::string test, reference, json, heatmap, heatmapSource = "ldr-flip";
    double epsilon = 1e-2, pixelsPerDegree = 67.0;
};

struct Results {
    double psnr = 0, ssim = 0, relMse = 0, flipLdr = 0, flipHdr = 0;
    std::vector<float> ldrMap, hdrMap;
};

std::string jsonString(const std::string& text) {
    std::string quoted = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') quoted += '\\';
        if (uint8_t(c) < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", unsigned(uint8_t(c)));
            quoted += escaped;
        } else {
            quoted += c;
        }
    }
    return quoted + "\"";
}

// JSON has no infinity: equal images give a PSNR of null.
std::string jsonNumber(double value) {
    if (!std::isfinite(value)) return "null";
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

void writeJson(const Options& options, const ripple::apps::LinearImage& image, const Results& results) {
    std::ostringstream out;
    out << "{\n  \"test\": " << jsonString(options.test) << ",\n  \"reference\": " << jsonString(options.reference)
        << ",\n  \"width\": " << image.width << ",\n  \"height\": " << image.height
        << ",\n  \"psnr\": " << jsonNumber(results.psnr) << ",\n  \"ssim\": " << jsonNumber(results.ssim)
        << ",\n  \"relMse\": " << jsonNumber(results.relMse) << ",\n  \"relMseEpsilon\": " << jsonNumber(options.epsilon)
        << ",\n  \"flipLdr\": " << jsonNumber(results.flipLdr) << ",\n  \"flipHdr\": " << jsonNumber(results.flipHdr)
        << ",\n  \"pixelsPerDegree\": " << jsonNumber(options.pixelsPerDegree) << "\n}\n";
    ripple::apps::writeFileAtomically(options.json, out.str(), "the JSON results");
}

// |test - reference| averaged over the channels, divided by its largest value so the map spans [0, 1].
std::vector<float> differenceMap(const ripple::apps::LinearImage& test, const ripple::apps::LinearImage& reference) {
    std::vector<float> map(size_t(test.width) * test.height);
    for (size_t p = 0; p < map.size(); ++p) {
        float sum = 0;
        for (size_t c = 0; c < 3; ++c) sum += std::abs(test.rgb[p * 3 + c] - reference.rgb[p * 3 + c]);
        map[p] = std::isfinite(sum) ? sum / 3 : 1.0f;
    }
    const float largest = *std::max_element(map.begin(), map.end());
    if (largest > 0)
        for (float& v : map) v /= largest;
    return map;
}

// Says on stderr how many channel values of `image` are NaN or infinite and where the first one is: the
// metrics still run (relMSE, PSNR and SSIM take them as they are; FLIP reads NaN and -infinity as black,
// +infinity as white), but are not to be trusted.
void warnNonFinite(const ripple::apps::LinearImage& image, const std::string& file) {
    size_t count = 0, first = 0;
    for (size_t i = 0; i < image.rgb.size(); ++i)
        if (!std::isfinite(image.rgb[i]) && count++ == 0) first = i / 3;
    if (count == 0) return;
    std::fprintf(stderr,
                 "[ripple-imgdiff] warning: %s holds %zu non-finite values (NaN or infinity), the first at pixel (%zu, %zu);"
                 " relMSE, PSNR and SSIM include them; FLIP reads NaN and -infinity as black, +infinity as white\n",
                 file.c_str(), count, first % image.width, first / image.width);
}

int run(const Options& options) {
    const ripple::apps::LinearImage test = ripple::apps::readLinearImage(options.test);
    const ripple::apps::LinearImage reference = ripple::apps::readLinearImage(options.reference);
    warnNonFinite(test, options.test);
    warnNonFinite(reference, options.reference);
    if (test.width != reference.width || test.height != reference.height)
        throw std::runtime_error("the images differ in size: " + options.test + " is " + std::to_string(test.width) + "x" +
                                 std::to_string(test.height) + ", " + options.reference + " is " +
                                 std::to_string(reference.width) + "x" + std::to_string(reference.height));
    Results results;
    results.psnr = ripple::apps::psnr(test, reference);
    results.ssim = ripple::apps::ssim(test, reference);
    results.relMse = ripple::apps::relMse(test, reference, options.epsilon);
    results.flipLdr = ripple::apps::flipLdr(test, reference, &results.ldrMap, options.pixelsPerDegree);
    results.flipHdr = ripple::apps::flipHdr(test, reference, &results.hdrMap, options.pixelsPerDegree);

    std::printf("size      %ux%u\n", test.width, test.height);
    std::printf("PSNR      %.4f dB\n", results.psnr);
    std::printf("SSIM      %.6f\n", results.ssim);
    std::printf("relMSE    %.6g (epsilon %g)\n", results.relMse, options.epsilon);
    std::printf("LDR-FLIP  %.6f (%.1f pixels per degree)\n", results.flipLdr, options.pixelsPerDegree);
    std::printf("HDR-FLIP  %.6f\n", results.flipHdr);
    if (!options.json.empty()) writeJson(options, test, results);
    if (!options.heatmap.empty()) {
        const std::vector<float> map = options.heatmapSource == "ldr-flip"   ? results.ldrMap
                                       : options.heatmapSource == "hdr-flip" ? results.hdrMap
                                                                             : differenceMap(test, reference);
        ripple::apps::writeHeatMap(options.heatmap, test.width, test.height, map);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"ripple-imgdiff: compares a test image with a reference (PNG, EXR, PFM). Prints PSNR (dB, of the\n"
                 "sRGB-encoded images clamped to [0, 1]), SSIM, relMSE = mean((test - ref)^2 / (ref^2 + epsilon)),\n"
                 "LDR-FLIP and HDR-FLIP (mean of the FLIP error map, 0 = identical, 1 = as different as can be)."};
    Options options;
    app.add_option("test", options.test, "the image to judge")->required();
    app.add_option("reference", options.reference, "the reference image")->required();
    app.add_option("--json", options.json, "also write the results as JSON to this file (PSNR null when infinite)");
    app.add_option("--heatmap", options.heatmap, "write a PNG heat map of the per-pixel error (magma colour map)");
    app.add_option("--heatmap-source", options.heatmapSource,
                   "what the heat map shows: ldr-flip, hdr-flip, or difference (|test - reference| over its maximum)")
        ->check(CLI::IsMember({"ldr-flip", "hdr-flip", "difference"}));
    app.add_option("--epsilon", options.epsilon, "relMSE's epsilon, keeping dark reference pixels from dominating")
        ->check(CLI::PositiveNumber);
    app.add_option("--ppd", options.pixelsPerDegree, "FLIP's pixels per degree of visual angle (67: 0.7 m from a 4K 0.7 m monitor)")
        ->check(CLI::Range(0.1, 1000.0));
    CLI11_PARSE(app, argc, argv);
    try {
        return run(options);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "[ripple-imgdiff] ERROR: %s\n", error.what());
        return 1;
    }
}
