// Ripple's programs run as a user runs them, for the tests that check their output, exit code and CSV
// reports: the command line goes through the shell, stdout and stderr come back together.
#pragma once

#include <doctest/doctest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace ripple::test {

struct ProgramRun {
    int exitCode = -1;      // -1: killed by a signal
    std::string output;     // stdout and stderr together
};

// Runs `program` with `arguments` (already quoted where needed) after the shell assignments in
// `environment`, stdout and stderr together.
inline ProgramRun runProgram(const std::string& program, const std::string& arguments, const std::string& environment = "") {
    const std::string command = environment + " '" + program + "' " + arguments + " 2>&1";
    ProgramRun run;
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::array<char, 512> chunk;
    size_t n;
    while ((n = fread(chunk.data(), 1, chunk.size(), pipe)) > 0) run.output.append(chunk.data(), n);
    const int status = pclose(pipe);
    run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

// Runs ripple-render with the Vulkan validation layers on in the device: a validation message becomes a
// device error, which makes ripple-render exit with 1.
inline ProgramRun runRender(const std::string& arguments) {
    return runProgram(RIPPLE_RENDER_PATH, arguments, "RIPPLE_VK_VALIDATION=1");
}

// The rows of a CSV file (header included), split at commas.
inline std::vector<std::vector<std::string>> readCsv(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> cells;
        std::stringstream cellStream(line);
        for (std::string cell; std::getline(cellStream, cell, ',');) cells.push_back(cell);
        rows.push_back(cells);
    }
    return rows;
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace ripple::test
