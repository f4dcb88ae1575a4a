// doctest entry point of the viewer's suite. `--requires-program=NAME` (ahead of doctest's own options) names
// a program the cases need on PATH (xvfb-run: a virtual X server); where it is absent nothing runs and the
// suite returns 77, which CMake declares as the test's SKIP_RETURN_CODE, so CTest reports it as skipped.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace {

constexpr const char kRequires[] = "--requires-program=";

bool onPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::stringstream folders(path ? path : "");
    for (std::string folder; std::getline(folders, folder, ':');) {
        std::error_code ec;
        const std::filesystem::path candidate = std::filesystem::path(folder.empty() ? "." : folder) / program;
        if (std::filesystem::is_regular_file(candidate, ec)) return true;
    }
    return false;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<char*> doctestArgs;
    for (int i = 0; i < argc; ++i) {
        if (i > 0 && std::strncmp(argv[i], kRequires, sizeof(kRequires) - 1) == 0) {
            const std::string program = argv[i] + sizeof(kRequires) - 1;
            if (!onPath(program)) {
                std::printf("skipped: %s is not installed (scripts/setup.sh installs it with xvfb)\n", program.c_str());
                return 77;
            }
            continue;
        }
        doctestArgs.push_back(argv[i]);
    }
    doctest::Context context(int(doctestArgs.size()), doctestArgs.data());
    return context.run();
}
