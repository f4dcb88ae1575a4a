// doctest entry point of the suites that need no MPI. `--requires=<path>` (repeatable, ahead of doctest's own
// options) names data a test needs: when one is absent the program runs nothing and returns kSkipped, which
// CMake declares as the test's SKIP_RETURN_CODE, so CTest reports the test as skipped, never as passed.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

namespace {

constexpr int kSkipped = 77;  // the automake convention; tests/*/CMakeLists.txt set SKIP_RETURN_CODE to it
constexpr const char kRequires[] = "--requires=";

}  // namespace

int main(int argc, char** argv) {
    std::vector<char*> doctestArgs;
    for (int i = 0; i < argc; ++i) {
        if (i > 0 && std::strncmp(argv[i], kRequires, sizeof(kRequires) - 1) == 0) {
            const char* path = argv[i] + sizeof(kRequires) - 1;
            std::error_code ec;
            if (!std::filesystem::exists(path, ec)) {
                std::printf("skipped: %s is absent (set RIPPLE_DATA_DIR)\n", path);
                return kSkipped;
            }
            continue;
        }
        doctestArgs.push_back(argv[i]);
    }
    doctest::Context context(int(doctestArgs.size()), doctestArgs.data());
    return context.run();
}
