// ripple-render run as a user runs it, for the tests that check its output and exit code: the command line
// goes through the shell, stdout and stderr come back together.
#pragma once

#include <doctest/doctest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace ripple::test {

struct RenderRun {
    int exitCode = -1;      // -1: killed by a signal
    std::string output;     // stdout and stderr together
};

// Runs ripple-render with the Vulkan validation layers on in the device: a validation message becomes a
// device error, which makes ripple-render exit with 1.
inline RenderRun runRender(const std::string& arguments) {
    const std::string command = std::string("RIPPLE_VK_VALIDATION=1 '") + RIPPLE_RENDER_PATH + "' " + arguments + " 2>&1";
    RenderRun run;
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::array<char, 512> chunk;
    size_t n;
    while ((n = fread(chunk.data(), 1, chunk.size(), pipe)) > 0) run.output.append(chunk.data(), n);
    const int status = pclose(pipe);
    run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace ripple::test
