// Nothing in the kernels assumes a subgroup size: ripple-render renders the same image, bit for bit, at
// lavapipe's three vector widths (LP_NATIVE_VECTOR_WIDTH 128, 256 and 512 bits: subgroups of 4, 8 and 16
// lanes; GPUs have 8 to 64), for every kind of scene and both traversal back-ends.
#include "tests/apps/ProgramRun.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using namespace ripple::test;

namespace {

std::string fileBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

}  // namespace

TEST_CASE("ripple-render: the same image at 4, 8 and 16 lanes") {
    TempFolder dir;
    // Linear float output: equal files are equal pixels.
    for (const std::string scene : {"--demo default", "--demo cornell", "--demo volume", "--demo isosurface",
                                    "--demo default --traversal rayQuery"}) {
        CAPTURE(scene);
        std::string reference;
        for (const int bits : {256, 128, 512}) {
            const std::filesystem::path image = dir / ("lanes" + std::to_string(bits) + ".pfm");
            const ProgramRun run = runProgram(RIPPLE_RENDER_PATH, scene + " --size 48x48 --spp 4 -q -o '" + image.string() + "'",
                                              "LP_NATIVE_VECTOR_WIDTH=" + std::to_string(bits));
            REQUIRE_MESSAGE(run.exitCode == 0, run.output);
            // The driver took the width: llvmpipe names it in the device line Ripple prints.
            CHECK_MESSAGE(contains(run.output, std::to_string(bits) + " bits)"), run.output);
            const std::string pixels = fileBytes(image);
            REQUIRE(!pixels.empty());
            if (reference.empty()) reference = pixels;
            else CHECK_MESSAGE(pixels == reference, bits << " bits differ from 256 bits");
        }
    }
}
