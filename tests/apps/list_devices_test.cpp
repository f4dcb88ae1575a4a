// ripple-render --list-devices as a user runs it: the Vulkan devices the Ripple device sees (on CI, lavapipe's
// one CPU device), the one it would render with marked, exit code 0; the overrides it honours; and a library
// that cannot list them.
#include "tests/apps/ProgramRun.h"

#include <doctest/doctest.h>

#include <cctype>
#include <string>

using namespace ripple::test;

namespace {

// The lines of the listing that name a device ("<index>: <name> (<kind>), driver ...").
int deviceLines(const std::string& output) {
    int lines = 0;
    for (size_t start = 0; start < output.size();) {
        const size_t end = output.find('\n', start);
        const std::string line = output.substr(start, end == std::string::npos ? std::string::npos : end - start);
        if (!line.empty() && std::isdigit(static_cast<unsigned char>(line[0])) && contains(line, "), driver "))
            ++lines;
        start = end == std::string::npos ? output.size() : end + 1;
    }
    return lines;
}

}  // namespace

TEST_CASE("ripple-render --list-devices lists lavapipe, marks the device it would take, and exits 0") {
    const ProgramRun run = runRender("--list-devices");
    CAPTURE(run.output);
    CHECK(run.exitCode == 0);
    CHECK(deviceLines(run.output) >= 1);
    CHECK(contains(run.output, "llvmpipe"));  // Mesa's lavapipe, which the CI machines have
    CHECK(contains(run.output, "(CPU), driver llvmpipe"));
    size_t chosen = 0;
    for (size_t at = run.output.find("[chosen]"); at != std::string::npos; at = run.output.find("[chosen]", at + 1)) ++chosen;
    CHECK(chosen == 1);
    CHECK_FALSE(contains(run.output, "rendered"));  // nothing is rendered or written
}

TEST_CASE("ripple-render --list-devices honours RIPPLE_VK_DEVICE, and says when it matches nothing") {
    const ProgramRun byName = runProgram(RIPPLE_RENDER_PATH, "--list-devices", "RIPPLE_VK_DEVICE=llvmpipe");
    CAPTURE(byName.output);
    CHECK(byName.exitCode == 0);
    CHECK(contains(byName.output, "[chosen]"));
    CHECK(contains(byName.output, "chosen by RIPPLE_VK_DEVICE \"llvmpipe\""));
    const ProgramRun none = runProgram(RIPPLE_RENDER_PATH, "--list-devices", "RIPPLE_VK_DEVICE=no-such-gpu");
    CAPTURE(none.output);
    CHECK(none.exitCode == 0);
    CHECK_FALSE(contains(none.output, "[chosen]"));
    CHECK(contains(none.output, "no device would be chosen: RIPPLE_VK_DEVICE \"no-such-gpu\" matches no Vulkan device"));
}

TEST_CASE("ripple-render --list-devices with a library that cannot be loaded fails with its name") {
    const ProgramRun run = runRender("--list-devices --library no_such_ripple_library");
    CHECK(run.exitCode == 1);
    CHECK(contains(run.output, "cannot load the ANARI library 'no_such_ripple_library'"));
}
