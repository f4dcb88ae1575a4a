// ripple-view as a user runs it: without a display it says what to do instead and exits with 1; under a
// virtual X server (xvfb-run) --screenshot renders the Cornell demo and writes the image ripple-render
// writes for the same scene, size and samples, also from a view-state file both read (with and without
// panel edits), and on Ripple's compositing device.
#include "io/image/ImageIO.h"
#include "tests/apps/ProgramRun.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>
#include <stb_image.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

using namespace ripple::test;

namespace {

// Runs ripple-view with the Vulkan validation layers on in the device (a validation message is a device
// error, which makes it exit with 1), after the shell words in `prefix` (an environment, xvfb-run).
ProgramRun runView(const std::string& arguments, const std::string& prefix) {
    return runProgram(RIPPLE_VIEW_PATH, arguments, "RIPPLE_VK_VALIDATION=1 " + prefix);
}

struct Image {
    int width = 0, height = 0;
    unsigned char* pixels = nullptr;  // RGBA8, row 0 at the top
    explicit Image(const std::filesystem::path& file) {
        int comp = 0;
        pixels = stbi_load(file.string().c_str(), &width, &height, &comp, 4);
    }
    ~Image() { stbi_image_free(pixels); }
    Image(const Image&) = delete;
    Image& operator=(const Image&) = delete;
    // Mean of channel c over columns [x0, x1) and rows [y0, y1).
    double mean(int x0, int x1, int y0, int y1, int c) const {
        double sum = 0.0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) sum += pixels[(y * width + x) * 4 + c];
        return sum / double((x1 - x0) * (y1 - y0));
    }
    double meanLuminance() const {
        return 0.2126 * mean(0, width, 0, height, 0) + 0.7152 * mean(0, width, 0, height, 1) +
               0.0722 * mean(0, width, 0, height, 2);
    }
};

}  // namespace

TEST_CASE("ripple-view without a display names the alternatives and exits with 1") {
    TempFolder dir;
    const auto image = dir / "never.png";
    const ProgramRun run = runView("--demo cornell --size 64x64 --frames 2 --screenshot '" + image.string() + "'",
                                   "env -u DISPLAY -u WAYLAND_DISPLAY");
    CHECK_MESSAGE(run.exitCode == 1, run.output);
    CHECK_MESSAGE(contains(run.output, "[ripple-view] ERROR: cannot open a window: no display (DISPLAY is not set)"),
                  run.output);
    CHECK_MESSAGE(contains(run.output, "ripple-render"), run.output);
    CHECK_MESSAGE(contains(run.output, "xvfb-run -a ripple-view"), run.output);
    CHECK_FALSE(std::filesystem::exists(image));
}

TEST_CASE("ripple-view refuses a screenshot it cannot write before opening a window") {
    TempFolder dir;
    const ProgramRun run = runView("--demo cornell --screenshot '" + (dir / "out.txt").string() + "'",
                                   "env -u DISPLAY -u WAYLAND_DISPLAY");
    CHECK_MESSAGE(run.exitCode == 1, run.output);
    CHECK_MESSAGE(contains(run.output, "--screenshot " + (dir / "out.txt").string() + ": unsupported image format '.txt'"),
                  run.output);
}

// The viewer's full-size passes of one sample accumulate as ripple-render's frames do (same device, seed,
// camera and batches), so the two images agree; the check allows any unbiased difference: mean luminance
// within 5%, and the Cornell box's red wall on the left and green on the right (margins as in
// render_cli_test's Cornell case, measured ratios 3.7 and 1.5); both report the same error estimate.
TEST_CASE("xvfb: ripple-view --screenshot renders the Cornell demo as ripple-render does") {
    TempFolder dir;
    const auto viewed = dir / "view.png", rendered = dir / "render.png";
    const ProgramRun view = runView("--demo cornell --size 64x64 --frames 8 --screenshot '" + viewed.string() + "'",
                                    "xvfb-run -a");
    REQUIRE_MESSAGE(view.exitCode == 0, view.output);
    CHECK_MESSAGE(contains(view.output, "wrote " + viewed.string() + " (64x64, 8 spp"), view.output);
    const ProgramRun render =
        runProgram(RIPPLE_RENDER_PATH, "--demo cornell --size 64x64 --spp 8 --quiet -o '" + rendered.string() + "'",
                   "RIPPLE_VK_VALIDATION=1");
    REQUIRE_MESSAGE(render.exitCode == 0, render.output);

    const Image a(viewed), b(rendered);
    REQUIRE(a.pixels != nullptr);
    REQUIRE(b.pixels != nullptr);
    CHECK(a.width == 64);
    CHECK(a.height == 64);
    const double meanA = a.meanLuminance(), meanB = b.meanLuminance();
    INFO("mean luminance: ripple-view " << meanA << ", ripple-render " << meanB);
    CHECK(meanB > 10.0);  // not black
    CHECK(std::abs(meanA - meanB) <= 0.05 * meanB);
    CHECK(a.mean(0, 8, 21, 43, 0) > 2.0 * a.mean(0, 8, 21, 43, 1));        // left: red
    CHECK(a.mean(56, 64, 21, 43, 1) > 1.25 * a.mean(56, 64, 21, 43, 0));   // right: green
    // The stats' error estimate is ripple-render's: the same samples dealt into the same halves give the same
    // number (to the printed digits and float rounding of the mapped averages).
    const auto estimateIn = [](const std::string& output) {
        const size_t at = output.rfind("estimated relMSE ");
        REQUIRE_MESSAGE(at != std::string::npos, output);
        return std::stod(output.substr(at + 17));
    };
    CHECK(estimateIn(view.output) == doctest::Approx(estimateIn(render.output)).epsilon(0.01));
}

// A view-state file (what V writes) read by both programs: the same camera, settings and size give the same
// image, pixel for pixel (the random numbers are keyed by pixel and sample, the stratified ones by the
// sample's place in its pass's sequence: both programs add one sample per pass here).
TEST_CASE("xvfb: a view file renders the same image in ripple-view and ripple-render") {
    TempFolder dir;
    const auto viewFile = dir / "view.json", viewed = dir / "view.png", rendered = dir / "render.png";
    {
        std::ofstream out(viewFile);
        out << R"({"ripple-view-state": 1,
                   "camera": {"type": "perspective", "position": [0.3, 0.2, 3.2], "direction": [-0.1, -0.05, -1],
                              "up": [0, 1, 0], "fovy": 0.6},
                   "renderer": {"subtype": "default", "pixelSamples": 1, "maxPathLength": 3, "ambientRadiance": 0.3,
                                "background": [0.2, 0.1, 0.05, 1]},
                   "size": [48, 32]})";
    }
    const ProgramRun view = runView("--demo cornell --view '" + viewFile.string() + "' --frames 4 --screenshot '" +
                                        viewed.string() + "'",
                                    "xvfb-run -a");
    REQUIRE_MESSAGE(view.exitCode == 0, view.output);
    CHECK_MESSAGE(contains(view.output, "(48x32, 4 spp"), view.output);
    const ProgramRun render = runProgram(RIPPLE_RENDER_PATH, "--demo cornell --view '" + viewFile.string() +
                                                                 "' --spp 4 --quiet -o '" + rendered.string() + "'",
                                         "RIPPLE_VK_VALIDATION=1");
    REQUIRE_MESSAGE(render.exitCode == 0, render.output);
    const Image a(viewed), b(rendered);
    REQUIRE(a.pixels != nullptr);
    REQUIRE(b.pixels != nullptr);
    REQUIRE(a.width == 48);
    REQUIRE(b.width == 48);
    REQUIRE(a.height == b.height);
    int differing = 0;
    for (int i = 0; i < a.width * a.height * 4; ++i) differing += a.pixels[i] != b.pixels[i] ? 1 : 0;
    CHECK(differing == 0);
    // Not the default view: the Cornell demo's own camera gives another image.
    const auto plain = dir / "plain.png";
    const ProgramRun other = runProgram(RIPPLE_RENDER_PATH, "--demo cornell --size 48x32 --spp 4 --quiet -o '" + plain.string() + "'",
                                        "RIPPLE_VK_VALIDATION=1");
    REQUIRE_MESSAGE(other.exitCode == 0, other.output);
    const Image c(plain);
    REQUIRE(c.pixels != nullptr);
    int different = 0;
    for (int i = 0; i < c.width * c.height * 4; ++i) different += c.pixels[i] != b.pixels[i] ? 1 : 0;
    CHECK(different > c.width * c.height);
}

// The panels' values in a view file (what V writes after editing the Lights and Volumes panels): a sun of
// another colour and strength, a denser volume of another colour map. Both programs apply them, pixel for
// pixel the same, and the image is not the one without them.
TEST_CASE("xvfb: a view file's light and volume values render the same in ripple-view and ripple-render") {
    TempFolder dir;
    const auto viewFile = dir / "view.json", cameraOnly = dir / "camera.json";
    const std::string head = R"({"ripple-view-state": 1,
        "camera": {"type": "perspective", "position": [0, 1.6, 4.4], "direction": [0, -0.3, -1], "up": [0, 1, 0],
                   "fovy": 0.7},
        "renderer": {"pixelSamples": 1, "maxPathLength": 3}, "size": [40, 30])";
    writeText(cameraOnly, head + "}");
    writeText(viewFile, head + R"(,
        "lights": [{"label": "sun", "color": [1, 0.4, 0.3], "intensity": 5, "direction": [0.3, -1, 0.2]}],
        "volumes": [{"label": "volume 0", "colors": [[0.9, 0.9, 0.2], [0.2, 0.9, 0.9]], "opacities": [0, 0.6, 0.3],
                     "valueRange": [0, 1], "unitDistance": 0.05}]})");
    const auto viewed = dir / "view.png", rendered = dir / "render.png", plain = dir / "plain.png";
    const ProgramRun view = runView("--demo volume --view '" + viewFile.string() + "' --frames 2 --screenshot '" +
                                        viewed.string() + "'",
                                    "xvfb-run -a");
    REQUIRE_MESSAGE(view.exitCode == 0, view.output);
    const ProgramRun render = runProgram(RIPPLE_RENDER_PATH, "--demo volume --view '" + viewFile.string() +
                                                                 "' --spp 2 --quiet -o '" + rendered.string() + "'",
                                         "RIPPLE_VK_VALIDATION=1");
    REQUIRE_MESSAGE(render.exitCode == 0, render.output);
    const ProgramRun other = runProgram(RIPPLE_RENDER_PATH, "--demo volume --view '" + cameraOnly.string() +
                                                                "' --spp 2 --quiet -o '" + plain.string() + "'",
                                        "RIPPLE_VK_VALIDATION=1");
    REQUIRE_MESSAGE(other.exitCode == 0, other.output);
    const Image a(viewed), b(rendered), c(plain);
    REQUIRE(a.pixels != nullptr);
    REQUIRE(b.pixels != nullptr);
    REQUIRE(c.pixels != nullptr);
    REQUIRE(a.width == 40);
    REQUIRE(b.width == 40);
    REQUIRE(c.width == 40);
    REQUIRE(a.height == b.height);
    REQUIRE(c.height == b.height);
    int differing = 0, edited = 0;
    for (int i = 0; i < a.width * a.height * 4; ++i) {
        differing += a.pixels[i] != b.pixels[i] ? 1 : 0;
        edited += c.pixels[i] != b.pixels[i] ? 1 : 0;
    }
    CHECK(differing == 0);
    CHECK(edited > a.width * a.height);
    // The redder sun: the lit floor's red over green rises (column means over the lower third).
    const int floorTop = 2 * a.height / 3;
    CHECK(b.mean(0, b.width, floorTop, b.height, 0) / b.mean(0, b.width, floorTop, b.height, 1) >
          1.2 * c.mean(0, c.width, floorTop, c.height, 0) / c.mean(0, c.width, floorTop, c.height, 1));
}

// ripple-view speaks ANARI only: on Ripple's compositing device (which passes the scene to a Ripple device
// under it) it shows what ripple-render renders through that library: the same linear EXR, to the bit.
TEST_CASE("xvfb: ripple-view on another ANARI device (ripple_ptc) renders ripple-render's image") {
    TempFolder dir;
    const auto viewed = dir / "view.exr", rendered = dir / "render.exr";
    const ProgramRun view =
        runView("--library ripple_ptc --demo cornell --size 48x32 --frames 4 --screenshot '" + viewed.string() + "'",
                "xvfb-run -a");
    REQUIRE_MESSAGE(view.exitCode == 0, view.output);
    const ProgramRun render = runProgram(RIPPLE_RENDER_PATH, "--library ripple_ptc --demo cornell --size 48x32 --spp 4 "
                                                             "--quiet -o '" + rendered.string() + "'",
                                         "RIPPLE_VK_VALIDATION=1");
    REQUIRE_MESSAGE(render.exitCode == 0, render.output);
    const ripple::apps::LinearImage a = ripple::apps::readLinearImage(viewed), b = ripple::apps::readLinearImage(rendered);
    REQUIRE(a.width == 48);
    REQUIRE(b.width == 48);
    REQUIRE(a.rgb.size() == b.rgb.size());
    size_t differing = 0;
    double sum = 0.0;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        differing += a.rgb[i] != b.rgb[i] ? 1 : 0;
        sum += a.rgb[i];
    }
    CHECK(differing == 0);
    CHECK(sum / double(a.rgb.size()) > 0.05);  // a lit box, not an empty frame
}
