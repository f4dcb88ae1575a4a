// ripple-imgdiff as a user runs it: equal images give zero error and infinite PSNR, black against white gives
// a white-hot heat map, and missing files, size mismatches and malformed headers end with exit code 1 and a
// message naming the fault.
#include "io/image/ImageIO.h"
#include "metrics/HeatMap.h"
#include "tests/apps/ProgramRun.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>
#include <stb_image.h>


#include <array>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

using namespace ripple::test;

namespace {

ProgramRun runImgdiff(const std::string& arguments) { return runProgram(RIPPLE_IMGDIFF_PATH, arguments); }

// Built with append: GCC 12 gives a false -Wrestrict for "'" + string + "'".
std::string quoted(const std::filesystem::path& file) {
    std::string text(1, '\'');
    text.append(file.string()).push_back('\'');
    return text;
}

std::filesystem::path writeConstantPfm(const std::filesystem::path& file, uint32_t width, uint32_t height, float value) {
    const std::vector<float> rgba(size_t(width) * height * 4, value);
    ripple::apps::writePfmBottomUp(file, width, height, rgba.data());
    return file;
}

}  // namespace

TEST_CASE("ripple-imgdiff: equal images, zero error, JSON written") {
    TempFolder dir;
    const auto image = writeConstantPfm(dir / "a.pfm", 8, 8, 0.25f);
    const auto json = dir / "out.json";
    const ProgramRun run = runImgdiff(quoted(image) + " " + quoted(image) + " --json " + quoted(json));
    CAPTURE(run.output);
    REQUIRE(run.exitCode == 0);
    CHECK(contains(run.output, "PSNR      inf dB"));
    CHECK(contains(run.output, "SSIM      1.000000"));
    CHECK(contains(run.output, "LDR-FLIP  0.000000"));
    CHECK(contains(run.output, "HDR-FLIP  0.000000"));
    std::ifstream in(json);
    std::stringstream text;
    text << in.rdbuf();
    CHECK(contains(text.str(), "\"psnr\": null"));
    CHECK(contains(text.str(), "\"flipLdr\": 0,"));
    CHECK(contains(text.str(), "\"width\": 8,"));
}

TEST_CASE("ripple-imgdiff: black against white, heat map at the top of the colour map everywhere") {
    TempFolder dir;
    const auto black = writeConstantPfm(dir / "black.pfm", 6, 4, 0.0f);
    const auto white = writeConstantPfm(dir / "white.pfm", 6, 4, 1.0f);
    for (const char* source : {"ldr-flip", "difference"}) {
        CAPTURE(source);
        const auto heat = dir / "heat.png";
        const ProgramRun run = runImgdiff(quoted(black) + " " + quoted(white) + " --heatmap " + quoted(heat) +
                                   " --heatmap-source " + source);
        CAPTURE(run.output);
        REQUIRE(run.exitCode == 0);
        int width = 0, height = 0, channels = 0;
        unsigned char* pixels = stbi_load(heat.string().c_str(), &width, &height, &channels, 3);
        REQUIRE(pixels != nullptr);
        CHECK(width == 6);
        CHECK(height == 4);
        // FLIP of black against white is about 0.97 (see image_metrics_test), the normalised difference 1:
        // both land in magma's last segment, between #fec287 and #fcfdbf.
        int outside = 0;
        for (int i = 0; i < width * height; ++i) outside += pixels[i * 3] < 0xfc || pixels[i * 3 + 1] < 0xc2;
        stbi_image_free(pixels);
        CHECK(outside == 0);
    }
}

// --heatmap-source difference: each pixel's mean absolute difference over the channels, divided by the
// largest. Against black, a test at 0.4 on the left half and 0.1 on the right gives 1 and 0.25: magma's
// colours of those, pixel for pixel (FLIP's map of the same pair is another picture).
TEST_CASE("ripple-imgdiff: the difference heat map is the normalised absolute difference") {
    TempFolder dir;
    const uint32_t width = 8, height = 4;
    std::vector<float> rgba(size_t(width) * height * 4, 1.0f);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            for (uint32_t c = 0; c < 3; ++c) rgba[(size_t(y) * width + x) * 4 + c] = x < width / 2 ? 0.4f : 0.1f;
    const auto test = dir / "test.pfm";
    ripple::apps::writePfmBottomUp(test, width, height, rgba.data());
    const auto black = writeConstantPfm(dir / "black.pfm", width, height, 0.0f);
    const auto heat = dir / "heat.png";
    const ProgramRun run =
        runImgdiff(quoted(test) + " " + quoted(black) + " --heatmap " + quoted(heat) + " --heatmap-source difference");
    REQUIRE_MESSAGE(run.exitCode == 0, run.output);
    int w = 0, h = 0, channels = 0;
    unsigned char* pixels = stbi_load(heat.string().c_str(), &w, &h, &channels, 3);
    REQUIRE(pixels != nullptr);
    REQUIRE(w == int(width));
    int wrong = 0;
    for (int i = 0; i < w * h; ++i) {
        const std::array<uint8_t, 3> want = ripple::apps::magma(i % w < int(width / 2) ? 1.0f : 0.25f);
        for (int c = 0; c < 3; ++c) wrong += pixels[i * 3 + c] != want[size_t(c)];
    }
    stbi_image_free(pixels);
    CHECK(wrong == 0);
}

TEST_CASE("ripple-imgdiff: non-finite values are counted and located in a warning, and the metrics still print") {
    TempFolder dir;
    const auto finite = writeConstantPfm(dir / "finite.pfm", 4, 3, 0.5f);
    const auto notANumber = writeConstantPfm(dir / "nan.pfm", 4, 3, std::numeric_limits<float>::quiet_NaN());
    const ProgramRun run = runImgdiff(quoted(notANumber) + " " + quoted(finite));
    CAPTURE(run.output);
    CHECK(run.exitCode == 0);
    CHECK(contains(run.output, "nan.pfm holds 36 non-finite values (NaN or infinity), the first at pixel (0, 0)"));
    CHECK(contains(run.output, "HDR-FLIP"));
    CHECK(!contains(run.output, "finite.pfm holds"));
}

TEST_CASE("ripple-imgdiff: missing files, size mismatch and malformed headers are clear errors") {
    TempFolder dir;
    const auto small = writeConstantPfm(dir / "small.pfm", 4, 4, 0.5f);
    const auto wide = writeConstantPfm(dir / "wide.pfm", 5, 4, 0.5f);
    const auto broken = writeText(dir / "broken.pfm", "PF\n4 four\n-1.0\n");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {quoted(dir / "absent.png") + " " + quoted(small), "absent.png: cannot open the image (no such file)"},
        {quoted(small) + " " + quoted(wide), "differ in size"},
        {quoted(broken) + " " + quoted(small), "height 'four'"},
        {quoted(small), "reference is required"},
        {quoted(small) + " " + quoted(small) + " --heatmap-source sideways", "sideways"},
    };
    for (const auto& [arguments, message] : cases) {
        const ProgramRun run = runImgdiff(arguments);
        CAPTURE(arguments);
        CAPTURE(run.output);
        CHECK(run.exitCode != 0);
        CHECK(run.exitCode != -1);
        CHECK(contains(run.output, message));
    }
    const ProgramRun help = runImgdiff("--help");
    CHECK(help.exitCode == 0);
    CHECK(contains(help.output, "relMSE = mean((test - ref)^2 / (ref^2 + epsilon))"));
}
