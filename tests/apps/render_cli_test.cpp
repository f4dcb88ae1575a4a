// ripple-render as a user runs it: every error must end the process with exit code 1 and a message naming
// the problem, never a crash (a crash shows as a signal); and one small render through the Ripple device.
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>
#include <stb_image.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>

using namespace ripple::test;

namespace {

struct Run {
    int exitCode = -1;      // -1: killed by a signal
    std::string output;     // stdout and stderr together
};

// Runs ripple-render with the Vulkan validation layers on in the device: a validation message becomes a
// device error, which makes ripple-render exit with 1.
Run runRender(const std::string& arguments) {
    const std::string command = std::string("RIPPLE_VK_VALIDATION=1 '") + RIPPLE_RENDER_PATH + "' " + arguments + " 2>&1";
    Run run;
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::array<char, 512> chunk;
    size_t n;
    while ((n = fread(chunk.data(), 1, chunk.size(), pipe)) > 0) run.output.append(chunk.data(), n);
    const int status = pclose(pipe);
    run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("ripple-render rejects bad input with a message and exit code 1") {
    TempFolder dir;
    std::string arguments, expected;
    SUBCASE("missing scene file") {
        arguments = "'" + (dir / "absent.glb").string() + "'";
        expected = "absent.glb: no such file";
    }
    SUBCASE("malformed glTF") {
        std::vector<uint8_t> bytes = glbBytes(triangleSource());
        bytes[1] = 'X';
        arguments = "'" + writeBytes(dir / "broken.glb", bytes).string() + "'";
        expected = "broken.glb: bad magic";
    }
    SUBCASE("library that does not exist") {
        arguments = "--library no_such_ripple_library --demo default";
        expected = "cannot load the ANARI library 'no_such_ripple_library'";
    }
    SUBCASE("unknown demo scene") {
        arguments = "--demo nonesuch --library no_such_ripple_library";
        expected = "unknown demo scene 'nonesuch' (known: default, cornell)";
    }
    SUBCASE("size that is not WIDTHxHEIGHT") {
        arguments = "--size 12by5";
        expected = "--size '12by5' is not WIDTHxHEIGHT";
    }
    SUBCASE("zero size") {
        arguments = "--size 0x10";
        expected = "each side must be 1 to 16384 pixels";
    }
    SUBCASE("scene file and demo together") {
        arguments = "'" + writeGlb(dir / "t.glb", triangleSource()).string() + "' --demo default";
        expected = "either a scene file or --demo";
    }
    const Run run = runRender(arguments);
    CHECK_MESSAGE(run.exitCode == 1, run.output);
    CHECK_MESSAGE(contains(run.output, "[ripple-render] ERROR: "), run.output);
    CHECK_MESSAGE(contains(run.output, expected), run.output);
}

TEST_CASE("ripple-render option errors from the parser exit non-zero") {
    const Run run = runRender("--spp 0");
    CHECK(run.exitCode > 0);
    CHECK(contains(run.output, "--spp"));
}

// The whole path through the Ripple device: a small Cornell box, checked by properties any correct render
// has even at 4 samples, with margins measured on a correct render (ratios 3.7, 1.5 and 3.1): the red wall
// (-X) shows on the left and the green (+X) on the right, and the upper back wall (rows 12-20, lit directly
// by the ceiling light) is brighter than the boxes' camera-facing sides below it (rows 33-41, lit only
// indirectly). A frame written with its rows or columns the wrong way round fails one of them.
TEST_CASE("ripple-render renders the Cornell demo through the Ripple device") {
    TempFolder dir;
    const auto image = dir / "cornell.png";
    const Run run = runRender("--demo cornell --size 48x48 --spp 4 --quiet -o '" + image.string() + "'");
    REQUIRE_MESSAGE(run.exitCode == 0, run.output);
    CHECK(contains(run.output, "rendered 48x48, 4 spp"));
    int w = 0, h = 0, comp = 0;
    unsigned char* pixels = stbi_load(image.string().c_str(), &w, &h, &comp, 4);
    REQUIRE(pixels != nullptr);
    CHECK(w == 48);
    CHECK(h == 48);
    // Mean of channel c over a rectangle of the PNG (row 0 at the top).
    const auto mean = [&](int x0, int x1, int y0, int y1, int c) {
        double sum = 0.0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) sum += pixels[(y * w + x) * 4 + c];
        return sum / double((x1 - x0) * (y1 - y0));
    };
    const auto luminance = [&](int x0, int x1, int y0, int y1) {
        return 0.2126 * mean(x0, x1, y0, y1, 0) + 0.7152 * mean(x0, x1, y0, y1, 1) + 0.0722 * mean(x0, x1, y0, y1, 2);
    };
    // The side walls fill the outer eighths of the image at mid height.
    CHECK(mean(0, 6, 16, 32, 0) > 2.0 * mean(0, 6, 16, 32, 1));        // left: red
    CHECK(mean(42, 48, 16, 32, 1) > 1.25 * mean(42, 48, 16, 32, 0));   // right: green
    CHECK(luminance(12, 36, 12, 20) > 2.0 * luminance(12, 36, 33, 41)); // lit wall above, shaded boxes below
    stbi_image_free(pixels);
}
